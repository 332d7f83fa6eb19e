"""Tests of tools/check_kit.py: its verdict on one kit's cases (judge), which failures a
stripped kit allows; the programs' stop check; the switchable kit's trace. The kits themselves are built by CI's check_kit run.

Run: python3 -m unittest -v test_check_kit   (ctest runs it as tools.check_kit)
"""

import contextlib
import io
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
import make_kit  # noqa: E402

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


class Solved(unittest.TestCase):
    """The kit with every exercise solved passes every test, whatever its label."""

    def test_every_label_must_pass(self):
        cases = [check_kit.CaseResult("stage03.a case", 3, True, ""),
                 check_kit.CaseResult("docs.figures", 0, False, "docs/stages/03-sphere.md:122: figure x: the page says '1'"),
                 check_kit.CaseResult("reliability.bad_input.camera_far_eye", 0, True, "")]
        report = check_kit.solved_report(cases, 1.0)
        self.assertEqual(len(report.problems), 1)
        self.assertIn("docs.figures: fails with every exercise solved", report.problems[0])
        self.assertIn("docs, reliability, stage03", report.notes[0])

    def test_all_passing_is_no_problem(self):
        report = check_kit.solved_report([check_kit.CaseResult("library.x", 0, True, "")], 1.0)
        self.assertEqual(report.problems, [])


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


class Leaks(unittest.TestCase):
    """The leak check: no kit holds a run of an exercise's distinctive lines outside the
    exercise's own region (check_kit.find_leaks, check_kit.check_leaks)."""

    def test_a_line_counts_without_comments_whitespace_and_rt_when_it_has_three_words(self):
        key = check_kit.leak_key
        self.assertEqual(key("    const real dd = glm::dot(d, d); // the book's a"), "constrealdd=glm::dot(d,d);")
        self.assertEqual(key("const rt::vec3 pc = r.origin - s.center;"), key("const vec3 pc = r.origin - s.center;"))
        self.assertEqual(key('out << "P6 // not a comment" << w;'), 'out<<"P6//notacomment"<<w;')
        for plain in ("}", "else {", "return false;", "return;", "(void)tmin;", "// const real t = 1;",
                      "#include <cmath>", "", "    * const real t = 1;"):
            self.assertIsNone(key(plain), plain)

    ANSWER_FILE = """
        #pragma once
        inline int solve(int a, int b)
        {
            // RT_EXERCISE_BEGIN(stage01: solve it)
            const int sum = a + b;
            const int twice = 2 * sum;
            if (twice > 100)
                return 100;
            const int result = twice - a;
            return result;
            // RT_EXERCISE_END
        }
    """
    STUB = """
        #pragma once
        inline int solve(int a, int b)
        {
            // RT_EXERCISE_BEGIN(stage01: solve it)
            (void)a;
            (void)b;
            throw rt::exercise_not_done("stage 01: solve it: see docs/student-guide.md");
            // RT_EXERCISE_END
        }
    """
    COPY = """
        // a test's helper that copies the answer, reformatted and with its comments
        int copied(int a, int b) {
            const int sum = a + b;  // as the book has it
            const int twice = 2 * sum;
            if (twice > 100) {
                return 100;
            }
            return twice - a;
        }
    """

    def leaks(self, texts):
        answer = textwrap.dedent(self.ANSWER_FILE).lstrip("\n")
        regions = make_kit.scan_file("include/rt/solve.hpp", answer, {1}, [])
        with tempfile.TemporaryDirectory() as tmp:
            (Path(tmp) / "include" / "rt").mkdir(parents=True)
            (Path(tmp) / "include" / "rt" / "solve.hpp").write_text(answer)
            answers = check_kit.reference_answers(Path(tmp), regions)
        return check_kit.find_leaks([(rel, textwrap.dedent(text).lstrip("\n")) for rel, text in texts], answers, {1})

    def test_an_answer_in_its_own_region_is_no_leak(self):
        self.assertEqual(self.leaks([("include/rt/solve.hpp", self.ANSWER_FILE)]), [])  # handed out solved
        self.assertEqual(self.leaks([("include/rt/solve.hpp", self.STUB)]), [])

    def test_three_distinctive_lines_in_a_row_elsewhere_are_a_leak_named_by_file_and_line(self):
        self.assertEqual(self.leaks([("include/rt/solve.hpp", self.STUB), ("tests/helper.hpp", self.COPY)]),
                         ["tests/helper.hpp:3: holds 3 lines of the answer to stage01: solve it "
                          "(from include/rt/solve.hpp:5)"])

    def test_two_lines_in_a_row_are_not(self):
        two = "const int sum = a + b;\nconst int twice = 2 * sum;\nconst int other = sum - 1;\n"
        self.assertEqual(self.leaks([("tests/helper.hpp", two)]), [])

    def test_another_region_holding_an_answer_is_a_leak(self):
        other = """
            inline int other(int a, int b)
            {
                // RT_EXERCISE_BEGIN(stage01: another)
                const int sum = a + b;
                const int twice = 2 * sum;
                if (twice > 100)
                    return 100;
                return 0;
                // RT_EXERCISE_END
            }
        """
        found = self.leaks([("include/rt/solve.hpp", self.STUB), ("include/rt/other.hpp", other)])
        self.assertEqual(len(found), 1)
        self.assertTrue(found[0].startswith("include/rt/other.hpp:4: holds 3 lines of the answer to stage01"), found)

    def test_no_kit_make_kit_writes_holds_an_answer_outside_its_region(self):
        report = check_kit.check_leaks(TOOLS.parent)
        self.assertEqual(report.problems, [])
        self.assertEqual(report.cases, len(make_kit.known_stages(TOOLS.parent)))  # --from-stage N, every N

    def test_a_copy_of_an_exercise_body_put_back_into_a_kit_test_fails_the_check(self):
        repo = TOOLS.parent
        regions = {r.title: r for r in make_kit.scan_repository(repo)}
        with tempfile.TemporaryDirectory() as tmp:
            kit = Path(tmp) / "kit"
            with contextlib.redirect_stdout(io.StringIO()):
                self.assertEqual(make_kit.main(["--all", str(kit)]), 0)
            self.assertEqual(check_kit.check_leaks(repo, [kit]).problems, [])
            # the stage-03 quadratic, as a test's helper comparing it with the stable method once held it
            sphere = regions["ray-sphere intersection"]
            body = (repo / sphere.path).read_text().split("\n")[sphere.begin_line:sphere.end_line - 1]
            first = next(k for k, line in enumerate(body) if check_kit.leak_key(line))  # its first line of code
            distinctive = sum(1 for line in body if check_kit.leak_key(line))
            helper = kit / "tests" / "sphere_accuracy.hpp"
            before = helper.read_text()
            opening = before.count("\n") + 3  # the copy's line "{" (after an empty line and its signature)
            helper.write_text(before + "\ninline bool textbook_copy(const rt::sphere& s, const rt::ray& r, real tmin, "
                              "real tmax, rt::hit_record& rec)\n{\n" + "\n".join(body) + "\n}\n")
            # Moller-Trumbore with a name changed, as a copy written from the paper would be
            triangle = regions["Moller-Trumbore ray-triangle intersection"]
            body = (repo / triangle.path).read_text().split("\n")[triangle.begin_line:triangle.end_line - 1]
            watertight = kit / "tests" / "library_watertight.cpp"
            watertight.write_text(watertight.read_text() + "\nbool mt_copy(const rt::triangle& tri, const rt::ray& r, "
                                  "real tmin, real tmax, rt::hit_record& rec)\n{\n" +
                                  "\n".join(body).replace("inv_det", "inv") + "\n}\n")
            problems = check_kit.check_leaks(repo, [kit]).problems
        self.assertEqual(len(problems), 2, problems)
        by_file = {p.split(":")[0]: p for p in problems}
        self.assertTrue(by_file["tests/sphere_accuracy.hpp"].startswith(
            f"tests/sphere_accuracy.hpp:{opening + 1 + first}: holds {distinctive} lines of the answer to stage03: "
            f"ray-sphere intersection (from {sphere.path}:{sphere.begin_line + 1 + first})"), problems)
        self.assertRegex(by_file["tests/library_watertight.cpp"],
                         r"^tests/library_watertight.cpp:\d+: holds [3-9] lines of the answer to stage04: "
                         r"Moller-Trumbore ray-triangle intersection \(from include/rt/intersection/triangle.hpp:\d+\)")


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
            (rt_dir / "core").mkdir(parents=True)
            (rt_dir / "core" / "error.hpp").write_text((TOOLS.parent / "include" / "rt" / "core" / "error.hpp").read_text() +
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
