"""A skip cannot hide a failure: a small CMake project registers its tests as
tests/CMakeLists.txt does (cmake/RtTestCases.cmake), with rt's doctest runner
(tests/doctest_main.cpp, RT_SKIP) and its cmake -P cases (tests/skip.cmake,
tests/script_case.sh), and ctest's verdict on each is checked: a case that skips and
then fails, or fails and then skips, is failed; one that only skips is skipped, with its
reason in the output; an unwritten exercise (rt::exercise_not_done) is a skip in a
library suite (--not-done-skips) and a failure in a stage's suite. The project builds
in about 30 s.

Run: python3 -m unittest -v test_skips   (ctest runs it as tools.skips)
"""

import os
import re
import shutil
import subprocess
import sys
import textwrap
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from grade_fixture import have_build_tools, temporary_folder  # noqa: E402

REPO = Path(__file__).resolve().parent.parent.parent

CASES = r'''
#include "rt_doctest.hpp"

#include <iostream>
#include <stdexcept>

#include <rt/core/error.hpp>

namespace {
int unwritten_exercise() { throw rt::exercise_not_done("stage 99: a toy exercise: see nowhere"); }
void goes_on_after_saying_skipped() { rt_test::skip_case("said skipped in a helper, and the case went on"); }
} // namespace

TEST_CASE("passes") { CHECK(1 + 1 == 2); }

TEST_CASE("skips") { RT_SKIP("the toy has no input here"); }

TEST_CASE("skips in a subcase, which ends the case")
{
    CHECK(2 * 2 == 4);
    SUBCASE("one") { RT_SKIP("one subcase cannot run"); }
    SUBCASE("two") { CHECK(2 * 2 == 5); } // never reached: doctest finds a subcase as it runs
}

TEST_CASE("skips in a helper, then fails")
{
    goes_on_after_saying_skipped();
    CHECK(1 + 1 == 3);
}

TEST_CASE("fails, then skips")
{
    CHECK(1 + 1 == 3);
    RT_SKIP("a skip after a failure");
}

TEST_CASE("prints the old marker, then fails")
{
    std::cout << "SKIPPED: the marker of a regular expression\n";
    CHECK(1 + 1 == 3);
}

TEST_CASE("waits for an exercise") { CHECK(unwritten_exercise() == 1); }

TEST_CASE("ends at an exercise") { unwritten_exercise(); }

TEST_CASE("waits for an exercise, and fails besides")
{
    CHECK(1 + 1 == 3);
    CHECK(unwritten_exercise() == 1);
}

TEST_CASE("throws something else") { throw std::runtime_error("not an exercise"); }
'''

PROJECT = r'''
cmake_minimum_required(VERSION 3.21)
project(skips_toy CXX)
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
list(APPEND CMAKE_MODULE_PATH "${RT_REPO}/cmake")
find_package(glm CONFIG REQUIRED)
find_package(doctest CONFIG REQUIRED)
include(doctest)
include(RtTestCases)
enable_testing()
foreach(kind IN ITEMS library stage)
  add_executable(toy_${kind} cases.cpp "${RT_REPO}/tests/doctest_main.cpp")
  target_include_directories(toy_${kind} PRIVATE "${RT_REPO}/include" "${RT_REPO}/tests")
  target_link_libraries(toy_${kind} PRIVATE glm::glm doctest::doctest)
endforeach()
rt_discover_cases(toy_library "library." library --not-done-skips)
rt_discover_cases(toy_stage "stage." stage)
foreach(case IN ITEMS passes skips skips_then_fails)
  rt_add_script_test(script.${case} "-DRT_REPO=${RT_REPO}" -P "${CMAKE_CURRENT_SOURCE_DIR}/${case}.cmake")
endforeach()
'''

SCRIPTS = {
    "passes.cmake": 'message(STATUS "checked")\n',
    "skips.cmake": 'include("${RT_REPO}/tests/skip.cmake")\nrt_skip("nothing to judge here")\nreturn()\n',
    # says it skips but goes on, and fails
    "skips_then_fails.cmake": 'include("${RT_REPO}/tests/skip.cmake")\nrt_skip("said skipped")\n'
                              'message(FATAL_ERROR "expected 1, found 2")\n',
}

# ctest's verdict on each test of the project: passed, failed or skipped
EXPECTED = {
    "passes": ("passed", "passed"),
    "skips": ("skipped", "skipped"),
    "skips in a subcase, which ends the case": ("skipped", "skipped"),
    "skips in a helper, then fails": ("failed", "failed"),
    "fails, then skips": ("failed", "failed"),
    "prints the old marker, then fails": ("failed", "failed"),
    "waits for an exercise": ("skipped", "failed"),       # (library suite, stage suite)
    "ends at an exercise": ("skipped", "failed"),
    "waits for an exercise, and fails besides": ("failed", "failed"),
    "throws something else": ("failed", "failed"),
}
SCRIPT_EXPECTED = {"script.passes": "passed", "script.skips": "skipped", "script.skips_then_fails": "failed"}


def run(command, cwd=None, timeout=600):
    p = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       timeout=timeout)
    return p.returncode, p.stdout


class SkipsCannotHideFailures(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not have_build_tools():
            raise unittest.SkipTest("needs cmake, ninja and a C++ compiler")
        cls.tmp = temporary_folder("skips")
        source, build = cls.tmp / "toy", cls.tmp / "build"
        source.mkdir()
        (source / "CMakeLists.txt").write_text(textwrap.dedent(PROJECT))
        (source / "cases.cpp").write_text(CASES)
        for name, text in SCRIPTS.items():
            (source / name).write_text(text)
        code, out = run(["cmake", "-S", str(source), "-B", str(build), "-G", "Ninja", f"-DRT_REPO={REPO}"])
        assert code == 0, out
        code, out = run(["cmake", "--build", str(build), "-j", "2"])
        assert code == 0, out
        cls.build = build
        junit = cls.tmp / "results.xml"
        cls.ctest_code, cls.ctest_output = run(["ctest", "--test-dir", str(build), "-j", "2",
                                                "--output-junit", str(junit)])
        cls.verdicts, cls.outputs = {}, {}
        for case in ET.parse(junit).getroot().iter("testcase"):
            name = case.get("name", "")
            status = case.get("status", "")
            verdict = ("failed" if case.find("failure") is not None or status == "fail"
                       else "skipped" if status == "notrun" or case.find("skipped") is not None else "passed")
            cls.verdicts[name] = verdict
            out = case.find("system-out")
            cls.outputs[name] = out.text if out is not None and out.text else ""

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_each_doctest_case_gets_its_verdict(self):
        for case, (library, stage) in EXPECTED.items():
            with self.subTest(case=case):
                self.assertEqual(self.verdicts.get("library." + case), library, self.outputs.get("library." + case))
                self.assertEqual(self.verdicts.get("stage." + case), stage, self.outputs.get("stage." + case))

    def test_each_script_case_gets_its_verdict(self):
        for name, verdict in SCRIPT_EXPECTED.items():
            with self.subTest(case=name):
                self.assertEqual(self.verdicts.get(name), verdict, self.outputs.get(name))

    def test_ctest_counts_the_skips_and_fails_the_run(self):
        self.assertNotEqual(self.ctest_code, 0)
        skipped = sum(1 for v in self.verdicts.values() if v == "skipped")
        self.assertEqual(skipped, 7)  # 4 library cases, 2 stage cases, 1 script
        self.assertRegex(self.ctest_output, r"\*\*\*Skipped")
        self.assertNotRegex(self.ctest_output, r"100% tests passed")

    def test_a_skip_says_why(self):
        self.assertIn("SKIPPED: the toy has no input here", self.outputs["library.skips"])
        self.assertIn("SKIPPED: nothing to judge here", self.outputs["script.skips"])
        self.assertIn("stage 99: a toy exercise", self.outputs["library.waits for an exercise"])

    def test_a_whole_run_skips_only_when_no_case_passed(self):
        exe = self.build / "toy_library"
        code, out = run([str(exe), "--test-case=skips"])
        self.assertEqual(code, 77, out)
        code, out = run([str(exe), "--test-case=passes,skips"])
        self.assertEqual(code, 0, out)
        self.assertIn("[rt] 1 case skipped, 1 passed, none failed (skipped: skips)", out)
        code, out = run([str(exe)])
        self.assertEqual(code, 1, out)
        code, out = run([str(self.build / "toy_stage"), "--test-case=ends at an exercise"])
        self.assertEqual(code, 1, out)

    def test_no_test_of_the_tree_is_judged_by_its_output(self):
        # a regular expression that marks a test skipped wins over its exit code
        word = "SKIP_" + "REGULAR_EXPRESSION"
        found = []
        for folder, dirs, files in os.walk(REPO):
            dirs[:] = [d for d in dirs if d not in (".git", "__pycache__") and not d.startswith("build")]
            for name in files:
                if name == "CMakeLists.txt" or name.endswith(".cmake"):
                    path = Path(folder) / name
                    if word in path.read_text(errors="replace"):
                        found.append(str(path.relative_to(REPO)))
        self.assertEqual(found, [], f"expected no {word} (a skip must be exit code 77), found it in these files")


if __name__ == "__main__":
    unittest.main()
