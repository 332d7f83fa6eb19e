"""Tests of tools/grade.py: weights, unpacking, scoring, reports, isolation of cases, and
one grading run end to end on a small reference made here (class EndToEnd, about a minute).

Run: python3 -m unittest discover -s tools/tests -v   (ctest runs it as tools.grade)
"""

import io
import json
import os
import shutil
import sys
import tarfile
import tempfile
import textwrap
import unittest
import zipfile
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))
import grade  # noqa: E402
import make_kit  # noqa: E402


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


class Submissions(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="grade-test-"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_zip_paths_outside_and_links_are_skipped(self):
        archive = self.tmp / "s.zip"
        with zipfile.ZipFile(archive, "w") as z:
            z.writestr("include/rt/sphere.hpp", "// mine\n")
            z.writestr("../evil.hpp", "// outside\n")
            z.writestr("/abs.hpp", "// absolute\n")
            z.writestr("__MACOSX/include/rt/._sphere.hpp", "junk")
            link = zipfile.ZipInfo("include/rt/link.hpp")
            link.external_attr = (0o120777 << 16)
            z.writestr(link, "/etc/passwd")
        out = self.tmp / "out"
        grade.unpack(archive, out)
        files = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file())
        self.assertEqual(files, ["abs.hpp", "include/rt/sphere.hpp"] if (out / "abs.hpp").exists()
                         else ["include/rt/sphere.hpp"])
        self.assertFalse((self.tmp / "evil.hpp").exists())

    def test_tar_gz_with_a_symlink(self):
        archive = self.tmp / "s.tar.gz"
        with tarfile.open(archive, "w:gz") as t:
            data = b"// mine\n"
            info = tarfile.TarInfo("repo/include/rt/camera.hpp")
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
        self.assertEqual(files, ["repo/include/rt/camera.hpp"])

    def test_not_an_archive(self):
        bad = self.tmp / "s.rar"
        bad.write_text("x")
        with self.assertRaises(grade.SubmissionError):
            grade.unpack(bad, self.tmp / "out")

    def test_the_rt_folder_is_found(self):
        layouts = {
            ("repo/include/rt/sphere.hpp", "repo/backup/rt/sphere.hpp"): "repo/include/rt",
            ("rt/sphere.hpp", "x/y/rt/camera.hpp"): "rt",
            ("sphere.hpp", "camera.hpp"): ".",
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


class Reports(unittest.TestCase):
    def suite(self, statuses, max_points=10, build_error=""):
        s = grade.Suite(3, False, "sphere", max_points, ["test_stage03_sphere"], build_error=build_error)
        s.cases = [grade.Case(f"case {k}", status) for k, status in enumerate(statuses)]
        return s

    def test_points_are_the_fraction_of_the_stage_cases_passed(self):
        # every case of a stage suite tests an exercise: each carries its share of the points
        self.assertEqual(self.suite(["passed", "passed", "failed", "failed"]).points, 5)
        self.assertEqual(self.suite(["passed", "passed", "passed", "failed"]).points, 7.5)
        self.assertEqual(self.suite(["passed", "timeout", "passed"]).points, 6.67)
        self.assertEqual(self.suite(["passed", "passed"]).points, 10)
        self.assertEqual(self.suite([]).points, 0)
        self.assertEqual(self.suite(["passed"], build_error="x.hpp:1:1: error: boom").points, 0)

    def test_gradescope_results(self):
        suites = [self.suite(["passed", "crashed"]),
                  self.suite([], build_error="include/rt/sphere.hpp:4:5: error: expected ';'")]
        suites[1].hidden = True
        results = grade.gradescope_results(suites, "after_published", "note", 12.5)
        self.assertEqual(results["score"], 5)
        self.assertEqual(results["execution_time"], 12)
        self.assertEqual([t["visibility"] for t in results["tests"]], ["visible", "after_published"])
        self.assertEqual([t["status"] for t in results["tests"]], ["failed", "failed"])
        self.assertEqual([t["max_score"] for t in results["tests"]], [10, 10])
        self.assertIn("include/rt/sphere.hpp:4:5: error: expected ';'", results["tests"][1]["output"])
        self.assertIn("case 1: crashed", results["tests"][0]["output"])
        for test in results["tests"]:
            self.assertEqual(set(test), {"name", "number", "score", "max_score", "status", "output", "visibility"})
        json.dumps(results)

    def test_junit_has_one_suite_per_stage_suite(self):
        suites = [self.suite(["passed", "failed"]), self.suite([], build_error="e")]
        root = grade.junit(suites)
        self.assertEqual(root.get("tests"), "3")
        self.assertEqual(root.get("failures"), "2")
        self.assertEqual([s.get("name") for s in root.iter("testsuite")], ["stage03", "stage03"])
        self.assertEqual(len(list(root.iter("failure"))), 2)

    def test_first_compiler_error(self):
        log = textwrap.dedent("""\
            [1/3] Building CXX object tests/CMakeFiles/x.dir/a.cpp.o
            FAILED: tests/CMakeFiles/x.dir/a.cpp.o
            /usr/bin/c++ -I/tmp/w/src/include -c /tmp/w/src/tests/a.cpp
            In file included from /tmp/w/src/tests/a.cpp:3:
            /tmp/w/src/include/rt/sphere.hpp:42:17: error: expected ';' before 'return'
               42 |     real t = 1
                  |               ^
            /tmp/w/src/include/rt/sphere.hpp:50:1: error: second error
            ninja: build stopped: subcommand failed.
        """)
        text = grade.first_compiler_error(log, ["/tmp/w/src"])
        self.assertTrue(text.startswith("include/rt/sphere.hpp:42:17: error: expected ';' before 'return'"), text)
        self.assertIn("real t = 1", text)
        self.assertNotIn("second error", text)


@unittest.skipUnless(os.name == "posix", "process groups and signals")
class Isolation(unittest.TestCase):
    def test_pass_fail_crash_and_hang(self):
        py = sys.executable
        self.assertEqual(grade.run_case([py, "-c", "print('ok')"], None, 10, 0)[0], "passed")
        self.assertEqual(grade.run_case([py, "-c", "raise SystemExit(1)"], None, 10, 0)[0], "failed")
        status, output, _ = grade.run_case([py, "-c", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)"],
                                           None, 10, 0)
        self.assertEqual(status, "crashed")
        self.assertIn("SIGSEGV", output)
        # a hang, with a child process that would outlive a plain kill
        status, output, seconds = grade.run_case(
            ["sh", "-c", "sleep 30 & sleep 30"], None, 0.5, 0)
        self.assertEqual(status, "timeout")
        self.assertLess(seconds, 10)


def have_build_tools():
    return all(shutil.which(t) for t in ("cmake", "ctest")) and (shutil.which("g++") or shutil.which("c++"))


FIXTURE_HEADER = """
    // fx.hpp - three exercises for the grader's end-to-end test.
    #pragma once

    namespace rt {

    inline int add(int a, int b)
    {
        // RT_EXERCISE_BEGIN(stage01: add)
        return a + b;
        // RT_EXERCISE_END
    }

    inline int deref(const int* p)
    {
        // RT_EXERCISE_BEGIN(stage02: deref)
        return *p;
        // RT_EXERCISE_END
    }

    inline int identity(int n)
    {
        // RT_EXERCISE_BEGIN(stage03: identity)
        return n;
        // RT_EXERCISE_END
    }

    } // namespace rt
"""

FIXTURE_TESTS = {
    "tests/stage01_add.cpp": """
        #include <doctest/doctest.h>
        #include <rt/fx.hpp>
        TEST_CASE("two and three make five") { CHECK(rt::add(2, 3) == 5); }
        TEST_CASE("minus two and two make zero") { CHECK(rt::add(-2, 2) == 0); }
    """,
    "tests/stage02_deref.cpp": """
        #include <doctest/doctest.h>
        #include <rt/fx.hpp>
        TEST_CASE("seven") { const int x = 7; CHECK(rt::deref(&x) == 7); }
        TEST_CASE("four") { const int x = 4; CHECK(rt::deref(&x) == 4); }
    """,
    "tests/stage03_identity.cpp": """
        #include <doctest/doctest.h>
        #include <rt/fx.hpp>
        TEST_CASE("one") { CHECK(rt::identity(1) == 1); }
        TEST_CASE("zero") { CHECK(rt::identity(0) == 0); }
    """,
}

# Student's answers: stage 01 right, stage 02 aborts on 7, stage 03 hangs on 0.
STUDENT_HEADER = FIXTURE_HEADER.replace("return *p;", "if (*p == 7)\n        std::abort();\n    return *p;").replace(
    "return n;", "volatile bool forever = n == 0;\n    while (forever) {\n    }\n    return n;").replace(
    "#pragma once", "#pragma once\n#include <cstdlib>")


@unittest.skipUnless(have_build_tools(), "needs cmake and a C++ compiler")
class EndToEnd(unittest.TestCase):
    """A small reference with rt's own CMake files, three stages of one exercise each."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="grade-e2e-"))
        ref = cls.tmp / "reference"
        for rel in ("CMakeLists.txt", "cmake", "tests/CMakeLists.txt", "tests/doctest_main.cpp",
                    "stages/CMakeLists.txt", "stages/common", "third_party", "include/rt/error.hpp",
                    "tools/make_kit.py", "tools/grade.py", "tools/kit_manifest.json"):
            source, destination = REPO / rel, ref / rel
            destination.parent.mkdir(parents=True, exist_ok=True)
            if source.is_dir():
                shutil.copytree(source, destination)
            else:
                shutil.copy2(source, destination)
        (ref / "include/rt/fx.hpp").write_text(textwrap.dedent(FIXTURE_HEADER).lstrip())
        for rel, text in FIXTURE_TESTS.items():
            (ref / rel).write_text(textwrap.dedent(text).lstrip())
        (ref / "tools/weights.json").write_text(json.dumps({
            "case_timeout_seconds": 3, "stage_timeout_seconds": 30,
            "stages": {"01": {"visible": 10, "hidden": 5}, "02": {"visible": 10}, "03": {"visible": 10}}}))
        hidden = cls.tmp / "hidden"
        hidden.mkdir()
        (hidden / "stage01_more.cpp").write_text(
            '#include <doctest/doctest.h>\n#include <rt/fx.hpp>\n'
            'TEST_CASE("negative") { CHECK(rt::add(-1, 1) == 0); }\n')
        cls.reference, cls.hidden, cls.cache = ref, hidden, cls.tmp / "cache"

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def grade(self, submission, name):
        out = self.tmp / name
        code = grade.main([str(submission), "--reference", str(self.reference), "--hidden", str(self.hidden),
                           "--out", str(out), "--cache", str(self.cache), "--work", str(self.tmp / "work")])
        self.assertEqual(code, 0)
        results = json.loads((out / "results.json").read_text())
        self.assertTrue((out / "junit.xml").is_file())
        return {t["name"].split(" (")[0] + (" hidden" if "hidden" in t["name"] else ""): t for t in results["tests"]}, results

    def student(self, header_text, name):
        folder = self.tmp / name / "include" / "rt"
        folder.mkdir(parents=True)
        (folder / "fx.hpp").write_text(textwrap.dedent(header_text).lstrip())
        return self.tmp / name

    def test_a_crash_and_a_hang_cost_only_their_own_stage(self):
        tests, results = self.grade(self.student(STUDENT_HEADER, "student"), "out-student")
        self.assertEqual(tests["Stage 01"]["score"], 10)   # no baseline: both cases test the exercise
        self.assertEqual(tests["Stage 01 hidden"]["score"], 5)
        self.assertEqual(tests["Stage 02"]["score"], 5)    # one crash of two
        self.assertIn("crashed", tests["Stage 02"]["output"])
        self.assertEqual(tests["Stage 03"]["score"], 5)    # one hang of two
        self.assertIn("timeout", tests["Stage 03"]["output"])
        self.assertEqual(results["score"], 25)

    def test_the_reference_scores_full_points_and_a_kit_none_for_its_stripped_stages(self):
        tests, results = self.grade(self.reference, "out-reference")
        self.assertEqual(results["score"], 35)
        kit = self.tmp / "kit"
        self.assertEqual(make_kit.main(["--source", str(self.reference), "--from-stage", "2", str(kit)]), 0)
        tests, results = self.grade(kit, "out-kit")
        self.assertEqual([tests[k]["score"] for k in ("Stage 01", "Stage 01 hidden", "Stage 02", "Stage 03")],
                         [10, 5, 0, 0])

    def test_a_submission_that_does_not_compile_scores_zero_with_the_first_error(self):
        broken = FIXTURE_HEADER.replace("return a + b;", "return a + ;")
        tests, results = self.grade(self.student(broken, "broken"), "out-broken")
        self.assertEqual(results["score"], 0)
        self.assertRegex(tests["Stage 02"]["output"], r"include/rt/fx\.hpp:\d+:\d+: error:")
        self.assertNotIn(str(self.tmp), tests["Stage 02"]["output"])

    def test_an_archive_without_rt_scores_zero_with_the_reason(self):
        archive = self.tmp / "empty.zip"
        with zipfile.ZipFile(archive, "w") as z:
            z.writestr("README.txt", "nothing here")
        tests, results = self.grade(archive, "out-empty")
        self.assertEqual(results["score"], 0)
        self.assertIn("no include/rt folder", tests["Stage 01"]["output"])


if __name__ == "__main__":
    unittest.main()
