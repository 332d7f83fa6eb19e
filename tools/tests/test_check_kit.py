"""Tests of tools/check_kit.py: its verdict on one kit's cases (judge), which failures a
stripped kit allows; the programs' stop check; the switchable kit's trace. The kits themselves are built by CI's check_kit run.

Run: python3 -m unittest -v test_check_kit   (ctest runs it as tools.check_kit)
"""

import os
import shutil
import subprocess
import sys
import tempfile
import textwrap
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(Path(__file__).resolve().parent))
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


class Trace(unittest.TestCase):
    """The switchable kit's trace (RT_KIT_TRACE): which stages' exercises each ctest test
    asked about, so that a stage reruns only the tests that reach it."""

    MAIN = ('#include <cstring>\n#include <rt/fixture.hpp>\n'
            'int main(int argc, char** argv) {\n'
            '    const char* what = argc > 1 ? argv[1] : "";\n'
            '    if (std::strcmp(what, "length") == 0) return int(rt::length({}));\n'
            '    if (std::strcmp(what, "first") == 0) return rt::first_of(0, 1.0);\n'
            '    return 0;\n}\n')

    def test_each_ctest_test_is_traced_with_the_stages_it_asked_about(self):
        import test_make_kit  # the switchable fixture (same folder)
        import make_kit
        compiler = shutil.which("g++") or shutil.which("clang++")
        if compiler is None or shutil.which("ctest") is None or not Path("/proc/self/stat").exists():
            self.skipTest("needs a C++ compiler, ctest and /proc")
        text = textwrap.dedent(test_make_kit.StrippedBodiesCompile.SOURCE).lstrip("\n")
        regions, errors = test_make_kit.scan(test_make_kit.StrippedBodiesCompile.SOURCE, path="include/rt/fixture.hpp")
        self.assertEqual(errors, [])
        regions[0].repeats = [2]  # "length" (stage 01) repeats a stage-02 answer: it asks about 1 and 2
        with tempfile.TemporaryDirectory() as tmp:
            tmp = Path(tmp)
            rt_dir = tmp / "include" / "rt"
            rt_dir.mkdir(parents=True)
            (rt_dir / "error.hpp").write_text((TOOLS.parent / "include" / "rt" / "error.hpp").read_text() +
                                              make_kit.KIT_CHECK_SWITCH)
            (rt_dir / "fixture.hpp").write_text(make_kit.switchable_text("include/rt/fixture.hpp", text, regions, {}))
            (tmp / "use.cpp").write_text(self.MAIN)
            exe = tmp / "use"
            p = subprocess.run([compiler, "-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror",
                                "-I", str(tmp / "include"), str(tmp / "use.cpp"), "-o", str(exe)],
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)
            build, folder = tmp / "build", tmp / "trace"
            build.mkdir()
            folder.mkdir()
            (build / "CTestTestfile.cmake").write_text(
                "".join(f'add_test({name} "{exe}" {name})\n' for name in ("length", "first", "none")))
            env = dict(os.environ, RT_KIT_TRACE=str(folder))
            env.pop("RT_KIT_STRIP", None)
            run = subprocess.run(["ctest", "--test-dir", str(build)], capture_output=True, text=True, env=env)
            self.assertEqual(run.returncode, 0, run.stdout)
            trace, why = check_kit.read_trace(build, folder, [])
            self.assertIsNotNone(trace, why)
            self.assertEqual(trace.asked, {"length": 0b110, "first": 0b100, "none": 0})
            self.assertEqual(trace.number, {"length": 1, "first": 2, "none": 3})
            # a process that no ctest test started cannot be placed: no trace, and why
            subprocess.run([str(exe), "first"], env=env, check=False)
            trace, why = check_kit.read_trace(build, folder, [])
            self.assertIsNone(trace)
            self.assertIn("outside every ctest test", why)
