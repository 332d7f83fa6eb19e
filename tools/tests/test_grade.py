"""Tests of tools/grade.py and tools/grading/: weights, unpacking, the exercise regions taken
from a submission (and those refused), scoring, reports, isolation of cases, and grading
runs end to end on a small reference made here (class EndToEnd, about a minute: one
cache shared by its cases).

Run: python3 -m unittest discover -s tools/tests -v   (ctest runs it as tools.grade)
"""

import csv
import io
import json
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
import textwrap
import unittest
import zipfile
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import grade  # noqa: E402
import make_kit  # noqa: E402
from grade_fixture import (scanner_off, FIXTURE_HEADER, HIDDEN_SUITE, dedent, have_build_tools,  # noqa: E402
                           make_fixture_reference, run_as_arguments, student_copy, temporary_folder)
from grading import splice  # noqa: E402
from grading.common import parse_stages  # noqa: E402


class Weights(unittest.TestCase):
    def load(self, text):
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp, "weights.json")
            path.write_text(textwrap.dedent(text))
            return grade.load_weights(path)

    def test_the_shipped_weights_load(self):
        w = grade.load_weights(TOOLS / "weights.json")
        self.assertGreater(w.points(1, "visible"), 0)
        self.assertIn(w.hidden_visibility, grade.VISIBILITIES)

    def test_defaults_and_overrides(self):
        w = self.load("""
            {"//": "comment", "default": {"visible": 4, "hidden": 1},
             "stages": {"02": {"visible": 7}, "03": {"hidden": 3}}, "case_timeout_seconds": 5}
        """)
        self.assertEqual((w.points(1, "visible"), w.points(1, "hidden")), (4, 1))
        self.assertEqual((w.points(2, "visible"), w.points(2, "hidden")), (7, 1))
        self.assertEqual((w.points(3, "visible"), w.points(3, "hidden")), (4, 3))
        self.assertEqual(w.case_timeout, 5)

    def test_errors_name_the_line(self):
        cases = {
            '{\n  "stages": {\n    "3": {"visible": 1}\n  }\n}': (':3: expected a two-digit stage', ),
            '{\n  "stages": {"03": {"visible": -1}}\n}': (':2: expected a number >= 0', ),
            '{\n  "hidden_visibility": "never"\n}': (':2: expected one of hidden', ),
            '{\n  "weights": {}\n}': (':2: expected one of', ),
            '{\n  "stages": {"03": {"visble": 2}}\n}': ('expected "visible" or "hidden"', ),
            '{ "stages": ': ('expected JSON', ),
        }
        for text, fragments in cases.items():
            with self.subTest(text=text):
                with self.assertRaises(grade.GradeError) as caught:
                    self.load(text)
                message = str(caught.exception)
                self.assertIn("weights.json:", message)
                for fragment in fragments:
                    self.assertIn(fragment, message)

    def test_stages_chosen_on_the_command_line(self):
        self.assertEqual(parse_stages(None, [1, 2, 3]), [1, 2, 3])
        self.assertEqual(parse_stages("3", [1, 2, 3]), [3])
        self.assertEqual(parse_stages("01, 3", [1, 2, 3]), [1, 3])
        self.assertEqual(parse_stages("2-3", [1, 2, 3]), [2, 3])
        for bad in ("4", "x", "1-4"):
            with self.subTest(bad=bad), self.assertRaises(grade.GradeError):
                parse_stages(bad, [1, 2, 3])


class Submissions(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="grader-test-"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_zip_paths_outside_and_links_are_skipped(self):
        archive = self.tmp / "s.zip"
        with zipfile.ZipFile(archive, "w") as z:
            z.writestr("include/rt/intersection/sphere.hpp", "// mine\n")
            z.writestr("../evil.hpp", "// outside\n")
            z.writestr("/abs.hpp", "// absolute\n")
            z.writestr("__MACOSX/include/rt/._sphere.hpp", "junk")
            link = zipfile.ZipInfo("include/rt/link.hpp")
            link.external_attr = (0o120777 << 16)
            z.writestr(link, "/etc/passwd")
        out = self.tmp / "out"
        grade.unpack(archive, out)
        files = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file())
        self.assertEqual(files, ["include/rt/intersection/sphere.hpp"])
        self.assertFalse((self.tmp / "evil.hpp").exists())

    def test_tar_gz_with_a_symlink(self):
        archive = self.tmp / "s.tar.gz"
        with tarfile.open(archive, "w:gz") as t:
            data = b"// mine\n"
            info = tarfile.TarInfo("repo/include/rt/camera/camera.hpp")
            info.size = len(data)
            t.addfile(info, io.BytesIO(data))
            link = tarfile.TarInfo("repo/include/rt/evil.hpp")
            link.type = tarfile.SYMTYPE
            link.linkname = "/etc/passwd"
            t.addfile(link)
            up = tarfile.TarInfo("../../up.hpp")
            up.size = len(data)
            t.addfile(up, io.BytesIO(data))
        out = self.tmp / "out"
        grade.unpack(archive, out)
        files = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file() or p.is_symlink())
        self.assertEqual(files, ["repo/include/rt/camera/camera.hpp"])

    def test_not_an_archive(self):
        bad = self.tmp / "s.rar"
        bad.write_text("x")
        with self.assertRaises(grade.SubmissionError):
            grade.unpack(bad, self.tmp / "out")

    def test_a_header_is_matched_by_its_path_then_its_name(self):
        kit = ["include/rt/intersection/sphere.hpp", "include/rt/camera/camera.hpp", "include/rt/rt.hpp",
               "include/rt/core/a.hpp", "include/rt/detail/a.hpp"]
        self.assertEqual(grade.reference_path("intersection/sphere.hpp", kit), "include/rt/intersection/sphere.hpp")
        self.assertEqual(grade.reference_path("sphere.hpp", kit), "include/rt/intersection/sphere.hpp")  # loose
        self.assertEqual(grade.reference_path("old/camera.hpp", kit), "include/rt/camera/camera.hpp")
        self.assertIsNone(grade.reference_path("a.hpp", kit))  # two of that name: no guess
        self.assertIsNone(grade.reference_path("mine.hpp", kit))

    def test_the_rt_folder_is_found(self):
        layouts = {
            ("repo/include/rt/intersection/sphere.hpp", "repo/backup/rt/intersection/sphere.hpp"): "repo/include/rt",
            ("rt/intersection/sphere.hpp", "x/y/rt/camera/camera.hpp"): "rt",
            ("sphere.hpp", "camera.hpp"): ".",
            ("hw/include/rt/rt.hpp", "hw/include/rt/intersection/sphere.hpp"): "hw/include/rt",
        }
        for files, expected in layouts.items():
            with self.subTest(files=files):
                root = Path(tempfile.mkdtemp(dir=self.tmp))
                for rel in files:
                    (root / rel).parent.mkdir(parents=True, exist_ok=True)
                    (root / rel).write_text("//\n")
                found = grade.find_rt_folder(root, ["sphere.hpp", "camera.hpp"])
                self.assertEqual(found.relative_to(root).as_posix(), expected)
        empty = Path(tempfile.mkdtemp(dir=self.tmp))
        (empty / "notes.txt").write_text("no code")
        with self.assertRaises(grade.SubmissionError):
            grade.find_rt_folder(empty, ["sphere.hpp"])


class Regions(unittest.TestCase):
    """Only the exercise regions come from a submission, and only plain C++ in them."""

    def check(self, *lines):
        return splice.check_body("include/rt/fx.hpp", 10, list(lines))

    def test_plain_code_is_accepted(self):
        accepted = [
            ("    return a + b;",),
            ("    const char* p = \"/* { #define\"; // } #include",
             "    /* { */ return p[0] == '{' ? 1'000 : 0x1p-3;"),
            ("    auto s = R\"x(", "  } #define )\" ", ")x\";", "    return s.size();"),
            ("    [[maybe_unused]] int v[2] = <% 1, 2 %>;", "    return v<:0:>;"),
            ("    auto f = [&](int x) { return x + a; };", "    return f(b);"),
            ("    return std::vector<::std::size_t>{1}.size();",),
        ]
        for lines in accepted:
            with self.subTest(lines=lines):
                self.assertEqual(self.check(*lines), "")

    def test_what_is_refused_names_its_line(self):
        refused = {
            ("    int x = 1;", "    #define CHECK(...) ((void)0)"):
                "include/rt/fx.hpp:11:5: expected no preprocessor directive in an exercise region, found #define",
            ("  /**/ #include </etc/passwd>",): "fx.hpp:10:8: expected no preprocessor directive",
            ("  %:undef CHECK",): "found #undef",
            ("    return 0;", "}", "int evil() {"): "fx.hpp:11:1: expected code that stays inside the function body",
            ("    if (a) {", "        return b;"): "fx.hpp:10:12: expected '}' for this '{'",
            ("    return 0; /* the rest of the file",): "expected */ closing this comment",
            ("    auto s = R\"x(never closed",): "expected the raw string closed inside the region",
            ("    return 0; // a comment \\",): "expected no backslash at the end of a line",
            ("    asm(\".incbin \\\"/etc/passwd\\\"\");",): "expected no inline assembly",
            ("    _Pragma(\"once\") return 0;",): "expected no pragma",
            ("    int (*p)() __attribute__((section(\".init_array\"))) = nullptr;",):
                "expected no compiler attribute",
            ("    [[gnu::section(\".init_array\")]] static int x = 0;",): "found [[gnu::",
            ("    const char* s = \"open;",): "expected the string closed on its line",
            ("    doctest::detail::g_cs = nullptr;",): "expected no use of the test framework",
        }
        for lines, fragment in refused.items():
            with self.subTest(lines=lines):
                message = self.check(*lines)
                self.assertIn(fragment, message)
                self.assertRegex(message, r"^include/rt/fx\.hpp:\d+:\d+: expected .*, found .*; ")

    def test_regions_are_read_and_matched_by_stage_and_title(self):
        text = dedent("""
            // a helper of mine, outside any region: ignored
            inline int f(int a)
            {
                // RT_EXERCISE_BEGIN(stage01: add)
                return a;
                // RT_EXERCISE_END
            }
            inline int g()
            {
                // RT_EXERCISE_BEGIN(stage02: deref)
                #include <cstdio>
                return 0;
                // RT_EXERCISE_END
            }
            // RT_EXERCISE_BEGIN(stage03: identity)
            // RT_EXERCISE_END
            // RT_EXERCISE_END
            // RT_EXERCISE_BEGIN(stage04: never closed)
        """)
        student = splice.read_student_file("include/rt/fx.hpp", text.replace("\n", "\r\n"))
        self.assertEqual(sorted(student.regions), [(1, "add"), (2, "deref"), (3, "identity"), (4, "never closed")])
        self.assertEqual(student.regions[(1, "add")].body, ["    return a;"])
        self.assertEqual(student.regions[(1, "add")].problem, "")
        self.assertIn("include/rt/fx.hpp:11:5: expected no preprocessor directive", student.regions[(2, "deref")].problem)
        self.assertEqual(student.regions[(3, "identity")].body, [])
        self.assertIn("expected RT_EXERCISE_END for this region, found the end of the file",
                      student.regions[(4, "never closed")].problem)
        self.assertTrue(any("found no open region" in n for n in student.notes))

    def test_composed_headers_keep_the_students_line_numbers(self):
        ref = dedent(FIXTURE_HEADER).replace("#include <rt/core/error.hpp>\n\n", "")   # the kit's body needs it
        regions = make_kit.scan_file("include/rt/fx.hpp", ref, {1, 2, 3}, [])
        mine = ref.replace("namespace rt {\n", "namespace rt {\n// two lines of mine\n// ignored\n", 1)
        mine = mine.replace("    return a + b;", "    int c = a + b;\n    return c;")
        student = splice.read_student_file("include/rt/fx.hpp", mine)
        add = student.regions[(1, "add")]
        composed = splice.compose("include/rt/fx.hpp", ref, regions, {0: add, 1: "stub"}, {}, student)
        lines = composed.text.split("\n")
        at = lines.index("    int c = a + b;") + 1
        self.assertEqual(composed.lines[at], mine.split("\n").index("    int c = a + b;") + 1)
        self.assertIn(at, composed.exact)
        self.assertIn('throw rt::exercise_not_done("stage 02: deref: see docs/student-guide.md");', composed.text)
        self.assertIn('#include "core/error.hpp"', composed.text)     # the kit's body needs it
        self.assertIn("    return n;", composed.text)              # region 2: the reference's
        self.assertEqual(splice.outside_differences(student, ref, regions), 7)   # "// two lines of mine"

    def test_a_template_exercise_needs_a_stand_in_for_each_parameter(self):
        from grading import judge
        tmp = temporary_folder("template")
        try:
            ref = make_fixture_reference(tmp)
            fx = ref / "include/rt/fx.hpp"
            self.assertEqual(len(judge.exercises(grade.Reference(ref, exclude=[]))), 3)
            fx.write_text(fx.read_text().replace("inline long identity(long n)", "template <class T>\nT identity(T n)"))
            with self.assertRaises(grade.GradeError) as e:
                judge.exercises(grade.Reference(ref, exclude=[]))
            self.assertRegex(str(e.exception), r"^include/rt/fx.hpp:\d+: expected an exercise that is a function, "
                                               r"or a template over Accelerator or HitItem .* found a template over T;")
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


class Reports(unittest.TestCase):
    def suite(self, statuses, max_points=10, build_error="", hidden=False):
        s = grade.Suite(3, hidden, "sphere", max_points, ["test_stage03_sphere"], build_error=build_error)
        s.cases = [grade.Case(f"case {k}", status) for k, status in enumerate(statuses)]
        return s

    def test_points_are_the_fraction_of_the_stage_cases_passed(self):
        self.assertEqual(self.suite(["passed", "passed", "failed", "failed"]).points, 5)
        self.assertEqual(self.suite(["passed", "passed", "passed", "failed"]).points, 7.5)
        self.assertEqual(self.suite(["passed", "timeout", "passed"]).points, 6.67)
        self.assertEqual(self.suite(["passed", "passed"]).points, 10)
        self.assertEqual(self.suite([]).points, 0)
        self.assertEqual(self.suite(["passed"], build_error="x.hpp:1:1: error: boom").points, 0)
        refused = self.suite(["passed"])
        refused.refused = "include/rt/x.hpp:3:5: expected no preprocessor directive ..."
        self.assertEqual(refused.points, 0)

    def test_gradescope_results(self):
        suites = [self.suite(["passed", "crashed"]),
                  self.suite([], build_error="include/rt/intersection/sphere.hpp:4:5: error: expected ';'", hidden=True)]
        results = grade.gradescope_results(suites, "after_published", "note", 12.5)
        self.assertEqual(results["score"], 5)
        self.assertEqual(results["execution_time"], 12)
        self.assertEqual([t["visibility"] for t in results["tests"]], ["visible", "after_published"])
        self.assertEqual([t["status"] for t in results["tests"]], ["failed", "failed"])
        self.assertEqual([t["max_score"] for t in results["tests"]], [10, 10])
        self.assertIn("include/rt/intersection/sphere.hpp:4:5: error: expected ';'", results["tests"][1]["output"])
        self.assertIn("case 1: crashed", results["tests"][0]["output"])
        for test in results["tests"]:
            self.assertEqual(set(test), {"name", "number", "score", "max_score", "status", "output", "visibility"})
        json.dumps(results)

    def test_not_run_is_not_a_timeout(self):
        s = self.suite(["passed", "not run", "not run"])
        self.assertEqual(s.remark(), "2 not run")
        self.assertEqual(s.not_run, 2)

    def test_junit_has_one_suite_per_stage_suite(self):
        suites = [self.suite(["passed", "failed"]), self.suite([], build_error="e")]
        root = grade.junit(suites)
        self.assertEqual(root.get("tests"), "3")
        self.assertEqual(root.get("failures"), "2")
        self.assertEqual([s.get("name") for s in root.iter("testsuite")], ["stage03", "stage03"])
        self.assertEqual(len(list(root.iter("failure"))), 2)

    def test_grades_csv(self):
        rows = [{"student": "bob", "stage01": "10.00", "total": "10.00", "status": "graded"},
                {"student": "al, ice", "total": "", "status": "not graded: no include/rt"}]
        text = grade.grades_csv(rows, [1, 3]).decode()
        parsed = list(csv.DictReader(io.StringIO(text)))
        self.assertEqual(list(parsed[0]), ["student", "stage01", "stage03", "total", "status"])
        self.assertEqual(parsed[1]["student"], "al, ice")

    def test_first_compiler_error(self):
        log = textwrap.dedent("""\
            [1/3] Building CXX object tests/CMakeFiles/x.dir/a.cpp.o
            FAILED: tests/CMakeFiles/x.dir/a.cpp.o
            /usr/bin/c++ -I/tmp/w/src/include -c /tmp/w/src/tests/a.cpp
            In file included from /tmp/w/src/tests/a.cpp:3:
            /tmp/w/src/include/rt/intersection/sphere.hpp:42:17: error: expected ';' before 'return'
               42 |     real t = 1
                  |               ^
            /tmp/w/src/include/rt/intersection/sphere.hpp:50:1: error: second error
            ninja: build stopped: subcommand failed.
        """)
        text = grade.first_compiler_error(log, ["/tmp/w/src"])
        self.assertTrue(text.startswith("include/rt/intersection/sphere.hpp:42:17: error: expected ';' before 'return'"), text)
        self.assertIn("real t = 1", text)
        self.assertNotIn("second error", text)


@unittest.skipUnless(os.name == "posix", "process groups and signals")
class Isolation(unittest.TestCase):
    """sandbox.run_judged: a case's status comes from the judge's verdict, written on its
    own descriptor, never from what the process prints. The judges here are small
    programs that write a verdict, or do not."""

    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="rt-isolation-"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def judge(self, body):
        """A judge program: Python running `body`, with `verdict(line)` writing to the verdict fd."""
        path = self.tmp / f"judge{len(list(self.tmp.iterdir()))}"
        path.write_text(f"#!{sys.executable}\nimport os, signal, subprocess, sys\n"
                        f"def verdict(text):\n    os.write(int(os.environ['RT_JUDGE_VERDICT_FD']), text.encode())\n"
                        + textwrap.dedent(body))
        path.chmod(0o755)
        return path

    def run_case(self, body, expected=1, timeout=10.0):
        from grading.sandbox import TestUser, run_judged
        me = TestUser("grader", os.getuid(), os.getgid())
        status, output, seconds, _ = run_judged(self.judge(body), "a case, with a comma", self.tmp / "none",
                                                self.tmp, timeout, 0, me, expected)
        return status, output, seconds

    PASSED = "verdict('case\\t1\\t3\\t0\\t0\\nend\\t1\\t0\\n')\n"

    def test_only_the_verdict_passes_a_case(self):
        self.assertEqual(self.run_case(self.PASSED)[0], "passed")
        # a forged doctest summary on stdout, and exit 0, with no verdict
        status, output, _ = self.run_case("print('[doctest] test cases: 1 | 1 passed | 0 failed')\n")
        self.assertEqual(status, "failed")
        self.assertIn("no verdict", output)
        # a case that failed, one cut short (no end line), one with fewer checks than the reference's run
        self.assertEqual(self.run_case("verdict('case\\t0\\t3\\t1\\t0\\nend\\t0\\t1\\n')\n")[0], "failed")
        self.assertEqual(self.run_case("verdict('case\\t1\\t3\\t0\\t0\\n')\n")[0], "failed")
        status, output, _ = self.run_case(self.PASSED, expected=4)
        self.assertEqual(status, "failed")
        self.assertIn("3 of the 4 checks", output)
        # a verdict, then a non-zero exit
        self.assertEqual(self.run_case(self.PASSED + "sys.exit(3)\n")[0], "failed")

    def test_crash_and_hang(self):
        status, output, _ = self.run_case("os.kill(os.getpid(), signal.SIGSEGV)\n")
        self.assertEqual(status, "crashed")
        self.assertIn("SIGSEGV", output)
        # a hang, with a child process that would outlive a plain kill
        status, output, seconds = self.run_case("subprocess.Popen(['sleep', '30'])\nimport time\ntime.sleep(30)\n",
                                                timeout=0.5)
        self.assertEqual(status, "timeout")
        self.assertLess(seconds, 10)

    def test_long_output_is_cut_and_the_filter_matches_names_with_commas(self):
        status, output, _ = self.run_case("print(sys.argv[1]); print('x' * 5_000_000); print('the end')\n"
                                          + self.PASSED)
        self.assertEqual(status, "passed")
        self.assertLess(len(output), 200_000)
        self.assertIn("bytes left out", output)
        self.assertTrue(output.rstrip().endswith("the end"))
        self.assertIn("--test-case=a case? with a comma", output)


    def test_two_grading_runs_never_share_a_uid_and_a_case_gets_one_processor(self):
        from grading.sandbox import BLOCK, Processors, TestUser, claim_uid_block, slot_user
        folder = self.tmp / "uids"
        first, second = claim_uid_block(folder), claim_uid_block(folder)
        self.assertNotEqual(first.index, second.index)
        root = TestUser("rtgrader", 999, 999, ["/usr/bin/setpriv", "--reuid=999", "--"], dedicated=True)
        uids = {slot_user(root, k, block).uid for block in (first, second) for k in range(3)}
        self.assertEqual(len(uids), 6, "every slot of both runs has a uid of its own")
        self.assertTrue(all(uid >= 3_000_000_000 for uid in uids))
        with self.assertRaises(grade.GradeError):
            first.uid(BLOCK)
        # a block is free again once its run has ended
        index = first.index
        del first
        self.assertEqual(claim_uid_block(folder).index, index)
        # the judge and the server of a case share a processor; two cases get two when there are
        processors = Processors()
        with processors.one() as a, processors.one() as b:
            if len(os.sched_getaffinity(0)) > 1:
                self.assertNotEqual(a, b)


def make_autograder(output, *options, source):
    return subprocess.run([sys.executable, str(TOOLS / "gradescope" / "make_autograder.py"), str(output),
                           "--source", str(source), *options], capture_output=True, text=True, timeout=300)


class AutograderZip(unittest.TestCase):
    """tools/gradescope/make_autograder.py (the autograder itself: test_autograder.py)."""

    def setUp(self):
        self.tmp = temporary_folder("zip")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_a_zip_written_inside_the_repository_never_goes_into_a_zip(self):
        ref = make_fixture_reference(self.tmp)
        if shutil.which("git"):
            subprocess.run(["git", "init", "-q", str(ref)], check=True)
        for name in ("autograder.zip", "autograder-week3.zip"):
            p = make_autograder(ref / name, "--stages", "2,3", source=ref)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("grades with --stages 2,3", p.stdout)
        with zipfile.ZipFile(ref / "autograder-week3.zip") as z:
            names = z.namelist()
            self.assertEqual(z.read("grade_args").decode().split(), ["--stages", "2,3"])
            self.assertEqual((z.getinfo("run_autograder").external_attr >> 16) & 0o777, 0o755)
        self.assertIn("setup.sh", names)
        self.assertIn("rt/include/rt/fx.hpp", names)
        self.assertFalse([n for n in names if n.endswith(".zip") or ".tmp-zip" in n], names)

    def test_stages_without_tests_are_refused(self):
        ref = make_fixture_reference(self.tmp)
        p = make_autograder(self.tmp / "a.zip", "--stages", "7", source=ref)
        self.assertEqual(p.returncode, 2)
        self.assertIn("--stages 7: expected stages with tests (01, 02, 03), found 07", p.stderr)
        self.assertFalse((self.tmp / "a.zip").exists())


# Student's answers: stage 01 right, stage 02 crashes on 7 (it reads through a null
# pointer), stage 03 hangs on 0.
STUDENT_HEADER = FIXTURE_HEADER.replace(
    "return *p;", "const volatile int* none = nullptr;\n        if (*p == 7)\n            return *none;\n"
                  "        return *p;").replace(
    "return n;", "volatile bool forever = n == 0;\n        while (forever) {\n        }\n        return n;")


@unittest.skipUnless(have_build_tools(), "needs cmake, ninja and a C++ compiler")
class EndToEnd(unittest.TestCase):
    """A small reference with rt's own CMake files, three stages of one exercise each; one
    cache for every case."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = temporary_folder("e2e")
        cls.reference = make_fixture_reference(cls.tmp)
        cls.hidden = cls.tmp / "hidden"
        cls.hidden.mkdir(mode=0o700)
        (cls.hidden / "stage01_more.cpp").write_text(HIDDEN_SUITE)
        cls.cache = cls.tmp / "cache"
        cls.count = 0

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def common(self):
        return ["--reference", str(self.reference), "--hidden", str(self.hidden), "--cache", str(self.cache),
                "--work", str(self.tmp / "work")] + run_as_arguments()

    def grade(self, submission, *options):
        EndToEnd.count += 1
        out = self.tmp / f"out-{self.count}"
        code = grade.main([str(submission), "--out", str(out)] + self.common() + list(options))
        self.assertEqual(code, 0)
        results = json.loads((out / "results.json").read_text())
        self.assertTrue((out / "junit.xml").is_file())
        return {t["name"].split(" (")[0] + (" hidden" if "hidden" in t["name"] else ""): t
                for t in results["tests"]}, results

    def student(self, header_text):
        EndToEnd.count += 1
        return student_copy(self.tmp / f"student-{self.count}", header_text)

    def test_a_crash_and_a_hang_cost_only_their_own_stage(self):
        tests, results = self.grade(self.student(STUDENT_HEADER))
        self.assertEqual(tests["Stage 01"]["score"], 10)
        self.assertEqual(tests["Stage 01 hidden"]["score"], 5)
        self.assertEqual(tests["Stage 02"]["score"], 5)    # one crash of two
        self.assertIn("crashed", tests["Stage 02"]["output"])
        self.assertEqual(tests["Stage 03"]["score"], 5)    # one hang of two
        self.assertIn("timeout", tests["Stage 03"]["output"])
        self.assertEqual(results["score"], 25)

    def test_the_reference_scores_full_points_and_a_kit_none_for_its_stripped_stages(self):
        tests, results = self.grade(self.reference)
        self.assertEqual(results["score"], 35)
        kit = self.tmp / "kit"
        self.assertEqual(make_kit.main(["--source", str(self.reference), "--from-stage", "2", str(kit)]), 0)
        tests, results = self.grade(kit)
        self.assertEqual([tests[k]["score"] for k in ("Stage 01", "Stage 01 hidden", "Stage 02", "Stage 03")],
                         [10, 5, 0, 0])
        # the assignment of that kit: stages 02 and 03 only; stage 01, handed out solved, is not shown
        tests, results = self.grade(kit, "--stages", "2,3")
        self.assertEqual(sorted(tests), ["Stage 02", "Stage 03"])
        self.assertEqual(results["score"], 0)
        self.assertNotRegex(results["output"], r"(?m)^01 ")

    def test_a_compile_error_costs_only_its_own_stage_unless_cumulative(self):
        broken = FIXTURE_HEADER.replace("return a + b;", "return a + ;")
        submission = self.student(broken)
        line = dedent(broken).split("\n").index("    return a + ;") + 1
        tests, results = self.grade(submission)
        self.assertEqual([tests[k]["score"] for k in ("Stage 01", "Stage 02", "Stage 03")], [0, 10, 10])
        self.assertRegex(tests["Stage 01"]["output"], rf"include/rt/fx\.hpp:{line}:\d+: error:")
        self.assertIn(f"{line:>5} |     return a + ;", tests["Stage 01"]["output"])
        self.assertNotIn(str(self.tmp), tests["Stage 01"]["output"])
        self.assertIn("Each stage judged alone", results["output"])
        # cumulative: every suite compiles the student's whole header, so none compiles
        tests, results = self.grade(submission, "--cumulative")
        self.assertEqual([tests[k]["score"] for k in ("Stage 01", "Stage 02", "Stage 03")], [0, 0, 0])
        self.assertRegex(tests["Stage 03"]["output"], rf"include/rt/fx\.hpp:{line}:\d+: error:")
        self.assertIn("Graded cumulatively", results["output"])

    def test_only_the_regions_come_from_a_submission(self):
        macros = "\n".join(f"#define {m}(...) ((void)0)" for m in ("CHECK", "REQUIRE", "CHECK_EQ"))
        cheat = FIXTURE_HEADER.replace("#include <cstdlib>", "#include <cstdlib>\n#include <doctest/doctest.h>\n"
                                       + macros.replace("\n", "\n    "))
        cheat = cheat.replace("return a + b;", "return 1;").replace("return *p;", "return 0;").replace(
            "return n;", "return T(42);")
        tests, results = self.grade(self.student(cheat))
        self.assertEqual(results["score"], 0)
        self.assertIn("expected the kit's lines outside the exercise regions", results["output"])

    def test_a_directive_inside_a_region_is_refused_with_its_line(self):
        refused = FIXTURE_HEADER.replace("        return *p;", "        #define CHECK(...) ((void)0)\n        return *p;")
        line = dedent(refused).split("\n").index("    #define CHECK(...) ((void)0)") + 1
        tests, results = self.grade(self.student(refused))
        self.assertEqual([tests[k]["score"] for k in ("Stage 01", "Stage 02", "Stage 03")], [10, 0, 10])
        self.assertIn(f"include/rt/fx.hpp:{line}:5: expected no preprocessor directive in an exercise region, "
                      f"found #define;", tests["Stage 02"]["output"])
        self.assertIn(f"refused: include/rt/fx.hpp:{line}:5", results["output"])

    def test_a_region_that_ends_the_program_early_does_not_pass(self):
        early = FIXTURE_HEADER.replace("return a + b;", "std::_Exit(0);")
        self.assertIn("found std::_Exit", splice.check_body("include/rt/fx.hpp", 1, ["    std::_Exit(0);"]))
        with scanner_off():     # the region scanner refuses it; the judge must stop it too
            tests, results = self.grade(self.student(early))
        self.assertEqual(tests["Stage 01"]["score"], 0)
        self.assertIn("your code ended the program (exit code 0): a function must return its answer, never end "
                      "the program", tests["Stage 01"]["output"])
        self.assertNotIn("no verdict", tests["Stage 01"]["output"])

    @unittest.skipUnless(run_as_arguments(), "the grader ends a case's leftovers only as root, with a test user")
    def test_processes_a_case_leaves_running_are_ended(self):
        daemon = FIXTURE_HEADER.replace(
            "return a + b;", 'std::system("setsid sleep 312 > /dev/null 2>&1 < /dev/null &");\n        return a + b;')
        with scanner_off():     # the region scanner refuses std::system; the sandbox must hold too
            tests, results = self.grade(self.student(daemon), "--stages", "1")
        self.assertEqual(tests["Stage 01"]["score"], 10)
        left = []
        for entry in os.listdir("/proc"):
            try:
                if entry.isdigit() and Path(f"/proc/{entry}/cmdline").read_bytes() == b"sleep\x00312\x00":
                    left.append(entry)
            except OSError:
                pass
        self.assertEqual(left, [])

    def test_hidden_suites_stay_out_of_the_top_level_output(self):
        tests, results = self.grade(self.reference)
        self.assertEqual(tests["Stage 01 hidden"]["visibility"], "after_published")
        self.assertNotRegex(results["output"].lower(), r"hidden")
        self.assertEqual(tests["Stage 01 hidden"]["score"], 5)

    def test_the_time_budget_leaves_cases_not_run_never_timed_out(self):
        tests, results = self.grade(self.student(STUDENT_HEADER), "--budget", "0")
        self.assertEqual(results["score"], 0)
        junit = (self.tmp / f"out-{self.count}" / "junit.xml").read_text()
        self.assertNotIn('message="timeout"', junit)
        self.assertIn("not run", results["output"])
        for name in ("Stage 01", "Stage 02", "Stage 03"):
            self.assertIn("time budget", tests[name]["output"])

    def test_an_archive_without_rt_scores_zero_with_the_reason(self):
        archive = self.tmp / "empty.zip"
        with zipfile.ZipFile(archive, "w") as z:
            z.writestr("README.txt", "nothing here")
        tests, results = self.grade(archive)
        self.assertEqual(results["score"], 0)
        self.assertIn("no include/rt folder", tests["Stage 01"]["output"])

    def test_a_batch_of_ten_writes_grades_csv(self):
        batch = self.tmp / "batch"
        batch.mkdir()
        answers = {
            "ann": FIXTURE_HEADER, "ben": STUDENT_HEADER,
            "cat": FIXTURE_HEADER.replace("return a + b;", "return a + ;"),
            "dan": FIXTURE_HEADER.replace("return *p;", "#include <cstdio>\n        return *p;"),
            "eve": FIXTURE_HEADER.replace("return n;", "return n + T(1);"),
            "fay": FIXTURE_HEADER, "gus": STUDENT_HEADER, "hal": FIXTURE_HEADER,
        }
        for name, header in answers.items():
            student_copy(batch / name, header)
        with zipfile.ZipFile(batch / "ivy.zip", "w") as z:       # an archive: the student is ivy
            z.writestr("rt/include/rt/fx.hpp", dedent(FIXTURE_HEADER))
        (batch / "jon").mkdir()                                   # nothing to grade
        (batch / "jon" / "notes.txt").write_text("forgot")
        out = self.tmp / "batch-out"
        code = grade.main(["--batch", str(batch), "--out", str(out), "--jobs", "2"] + self.common())
        self.assertEqual(code, 0)
        rows = {r["student"]: r for r in csv.DictReader(io.StringIO((out / "grades.csv").read_text()))}
        self.assertEqual(sorted(rows), sorted(list(answers) + ["ivy", "jon"]))
        totals = {name: rows[name]["total"] for name in rows}
        self.assertEqual(totals, {"ann": "35.00", "ben": "25.00", "cat": "20.00", "dan": "25.00", "eve": "25.00",
                                  "fay": "35.00", "gus": "25.00", "hal": "35.00", "ivy": "35.00", "jon": "0.00"})
        self.assertEqual(rows["ann"]["stage01"], "15.00")          # visible and hidden together
        self.assertEqual(rows["ann"]["status"], "graded")
        self.assertTrue(rows["jon"]["status"].startswith("not graded: no include/rt folder"))
        self.assertTrue((out / "ivy" / "results.json").is_file())


if __name__ == "__main__":
    unittest.main()
