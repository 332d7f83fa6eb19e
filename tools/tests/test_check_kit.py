"""Tests of tools/check_kit.py's verdict on one kit's cases (judge): which failures a stripped
kit allows. The kits themselves are built by CI's check_kit run.

Run: python3 -m unittest -v test_check_kit   (ctest runs it as tools.check_kit)
"""

import sys
import tempfile
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(TOOLS))
import check_kit  # noqa: E402

NOT_DONE_02 = 'THREW exception: "stage 02: quantise to 8 bits: see docs/stages/02-generate-rays.md"'
NOT_DONE_08 = "THREW exception: stage 08: clamp tone map: see docs/stages/08-output.md"


def judged(cases, stripped):
    report = check_kit.KitReport("kit")
    check_kit.judge(report, [check_kit.CaseResult(*c) for c in cases], set(stripped), {})
    return report


class Judge(unittest.TestCase):
    def test_a_stripped_stage_fails_with_its_own_message(self):
        report = judged([("stage02.a", 2, False, NOT_DONE_02), ("stage08.b", 8, True, "")], {2})
        self.assertEqual(report.problems, [])
        self.assertEqual((report.passed, report.not_done), (1, 1))

    def test_a_stage_calling_another_stages_exercise_is_named(self):
        report = judged([("stage02.a", 2, False, NOT_DONE_02), ("stage08.a", 8, False, NOT_DONE_08),
                         ("stage08.b", 8, False, NOT_DONE_02)], {2, 8})
        self.assertEqual(len(report.problems), 1)
        self.assertIn("calls stage 02's exercise", report.problems[0])

    def test_a_solved_stage_must_pass(self):
        report = judged([("stage02.a", 2, False, NOT_DONE_02), ("stage08.a", 8, False, NOT_DONE_02)], {2})
        self.assertEqual(len(report.problems), 1)
        self.assertIn("stage 08 is solved in this kit", report.problems[0])

    def test_a_library_case_may_wait_for_a_stripped_stage(self):
        report = judged([("stage02.a", 2, False, NOT_DONE_02),
                         ("library.save", 0, False, NOT_DONE_02)], {2})
        self.assertEqual(report.problems, [])
        self.assertEqual(report.library_not_done, 1)

    def test_a_library_case_may_not_wait_for_a_solved_stage(self):
        report = judged([("stage02.a", 2, False, NOT_DONE_02),
                         ("library.save", 0, False, NOT_DONE_08)], {2})
        self.assertEqual(len(report.problems), 1)
        self.assertIn("library.save: failed", report.problems[0])

    def test_a_library_case_failing_otherwise_is_a_problem(self):
        report = judged([("stage02.a", 2, False, NOT_DONE_02),
                         ("library.bvh", 0, False, "ERROR: CHECK( 3 == 4 ) is NOT correct!")], {2})
        self.assertEqual(len(report.problems), 1)

    def test_a_stripped_stage_without_failures_cannot_fail(self):
        report = judged([("stage03.a", 3, True, "")], {3})
        self.assertIn("none of its cases fails", report.problems[0])


class ProgramsStop(unittest.TestCase):
    """check_programs_stop: each stage program runs once with every later stage stripped
    and must exit 0; a program that reaches a later stage's code (exit 3) is named."""

    def kit(self, folder: Path, reaches: dict) -> Path:
        # stages/NN_x/main.cpp marks a program; build/stages/stageNN_x is a script that
        # exits 3 when RT_KIT_STRIP names a stage it reaches, else 0
        for number, later in reaches.items():
            name = f"{number:02d}_s"
            (folder / "stages" / name).mkdir(parents=True)
            (folder / "stages" / name / "main.cpp").write_text("int main() {}\n")
            exe = folder / "build" / "stages" / f"stage{name}"
            exe.parent.mkdir(parents=True, exist_ok=True)
            checks = "".join(f'case ",$RT_KIT_STRIP," in *,{s},*) echo "not done yet: stage {s:02d}" >&2; exit 3;; esac\n'
                             for s in later)
            exe.write_text("#!/bin/sh\n" + checks + "exit 0\n")
            exe.chmod(0o755)
        (folder / "scenes").mkdir()
        return folder

    def run_stop(self, reaches: dict):
        with tempfile.TemporaryDirectory() as d:
            kit = self.kit(Path(d), reaches)
            report = check_kit.KitReport("programs")
            check_kit.check_programs_stop(report, kit, kit / "build", sorted(reaches))
            return report

    def test_programs_that_stop_at_their_stage_pass(self):
        report = self.run_stop({1: [], 2: [], 3: []})
        self.assertEqual(report.problems, [])
        self.assertEqual((report.cases, report.passed), (2, 2))  # the last stage has no later one

    def test_a_program_reaching_a_later_stage_is_named(self):
        report = self.run_stop({1: [], 2: [3], 3: []})
        self.assertEqual(len(report.problems), 1)
        self.assertIn("stage02_s", report.problems[0])
        self.assertIn("03", report.problems[0])


if __name__ == "__main__":
    unittest.main()
