"""tools/gradescope: the autograder run as Gradescope runs it: the zip of make_autograder.py
unpacked into a fake /autograder (AUTOGRADER_ROOT), setup.sh (without apt-get), then
run_autograder on submissions to this repository's stage 03 (`--stages 3`, so the cache
holds one stage: about 30 s in all). The zip itself is tested in test_grade.py.

The Gradescope case needs root (setup.sh creates the test user and closes the sources to it)
and setpriv; without them its tests skip, with the reason (run_suite.py then exits 77).

Run: python3 -m unittest -v test_autograder   (ctest runs it as tools.autograder)
RT_GRADE_TEST_REFERENCE=DIR makes the autograder of another checkout of rt instead of this one.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import unittest
import zipfile
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from grade_fixture import have_build_tools, temporary_folder  # noqa: E402

REFERENCE = Path(os.environ.get("RT_GRADE_TEST_REFERENCE", str(TOOLS.parent))).resolve()
MAKE_AUTOGRADER = TOOLS / "gradescope" / "make_autograder.py"
DOCTEST_MACROS = ["CHECK", "CHECK_FALSE", "CHECK_MESSAGE", "CHECK_EQ", "CHECK_NE", "CHECK_LT", "CHECK_GT",
                  "CHECK_LE", "CHECK_GE", "CHECK_UNARY", "CHECK_THROWS", "CHECK_THROWS_AS", "CHECK_THROWS_WITH",
                  "CHECK_NOTHROW", "REQUIRE", "REQUIRE_FALSE", "REQUIRE_MESSAGE", "REQUIRE_EQ", "REQUIRE_THROWS",
                  "REQUIRE_THROWS_AS", "REQUIRE_NOTHROW", "REQUIRE_UNARY", "FAIL", "FAIL_CHECK", "WARN", "INFO",
                  "CAPTURE"]


def make_zip(output: Path, *options: str, source: Path = REFERENCE) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(MAKE_AUTOGRADER), str(output), "--source", str(source), *options],
                          capture_output=True, text=True, timeout=300)


def gradescope_skip_reason() -> str:
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return "not root: setup.sh creates the test user and closes /autograder/source to it"
    if not shutil.which("setpriv"):
        return "no setpriv: the tests of a submission run as another user through it"
    if not have_build_tools():
        return "needs cmake, ninja and a C++ compiler"
    return ""


SPHERE = "intersection/sphere.hpp"  # under include/rt
VEC = "core/vec.hpp"


class Gradescope(unittest.TestCase):
    """The autograder of stage 03, in a fake /autograder."""

    @classmethod
    def setUpClass(cls):
        reason = gradescope_skip_reason()
        if reason:
            raise unittest.SkipTest(reason)
        cls.tmp = temporary_folder("ag")
        cls.root = cls.tmp / "autograder"
        for sub in ("source", "submission", "results"):
            (cls.root / sub).mkdir(parents=True)
        os.chmod(cls.root, 0o755)
        p = make_zip(cls.tmp / "autograder.zip", "--stages", "3")
        assert p.returncode == 0, p.stderr
        with zipfile.ZipFile(cls.tmp / "autograder.zip") as z:
            z.extractall(cls.root / "source")
        for name in ("setup.sh", "run_autograder"):
            os.chmod(cls.root / "source" / name, 0o755)
        cls.env = dict(os.environ, AUTOGRADER_ROOT=str(cls.root), RT_AUTOGRADER_SKIP_APT="1")
        p = subprocess.run([str(cls.root / "source" / "setup.sh")], env=cls.env, capture_output=True, text=True,
                           timeout=900)
        assert p.returncode == 0, p.stdout + p.stderr
        cls.original = {name: (REFERENCE / "include" / "rt" / name).read_text()
                        for name in (SPHERE, VEC)}

    @classmethod
    def tearDownClass(cls):
        if hasattr(cls, "tmp"):
            shutil.rmtree(cls.tmp, ignore_errors=True)

    def run_autograder(self, files):
        """Grades a submission of include/rt holding the reference's headers, with `files`
        (name -> text) in place of theirs; returns results.json."""
        submission = self.root / "submission"
        shutil.rmtree(submission)
        shutil.copytree(REFERENCE / "include" / "rt", submission / "include" / "rt")
        for name, text in files.items():
            (submission / "include" / "rt" / name).write_text(text)
        results = self.root / "results" / "results.json"
        if results.exists():
            results.unlink()
        p = subprocess.run([str(self.root / "source" / "run_autograder")], env=self.env, capture_output=True,
                           text=True, timeout=900)
        self.assertEqual(p.returncode, 0, p.stderr)
        return json.loads(results.read_text())

    def sphere_with(self, body):
        """sphere.hpp with stage 03's region holding `body`."""
        text = self.original[SPHERE]
        return re.sub(r"(// RT_EXERCISE_BEGIN\(stage03: [^)]*\)\n).*?(\n[ \t]*// RT_EXERCISE_END)",
                      lambda m: m.group(1) + body + m.group(2), text, count=1, flags=re.S)

    @staticmethod
    def stage03(results):
        tests = [t for t in results["tests"] if t["name"].startswith("Stage 03")]
        assert tests, results
        return tests

    def test_only_stage_03_is_graded(self):
        results = self.run_autograder({})
        self.assertEqual({t["name"][:8] for t in results["tests"]}, {"Stage 03"})
        self.assertEqual(results["score"], sum(t["max_score"] for t in results["tests"]))

    def test_doctest_macros_defined_in_another_header_change_nothing(self):
        cheat = self.original[VEC].rstrip() + "\n#include <doctest/doctest.h>\n" + "\n".join(
            f"#undef {m}\n#define {m}(...) ((void)0)" for m in DOCTEST_MACROS) + "\n"
        unused = "    (void)s;\n    (void)r;\n    (void)tmin;\n    (void)tmax;\n    (void)rec;\n"
        # claiming a hit for every ray passes no case of stage 03
        results = self.run_autograder({VEC: cheat, SPHERE: self.sphere_with(unused + "    return true;")})
        self.assertEqual([t["score"] for t in self.stage03(results)], [0.0])
        self.assertIn("include/rt/core/vec.hpp: expected the kit's header, found another", results["output"])
        # the body of the report, `return false;`, scores what it scores without the macros
        with_macros = self.run_autograder({VEC: cheat, SPHERE: self.sphere_with(unused + "    return false;")})
        without = self.run_autograder({SPHERE: self.sphere_with(unused + "    return false;")})
        self.assertEqual(self.stage03(with_macros)[0]["score"], self.stage03(without)[0]["score"],
                         self.stage03(with_macros)[0]["output"][:3000])
        self.assertLess(self.stage03(with_macros)[0]["score"], self.stage03(with_macros)[0]["max_score"])

    def test_a_directive_in_the_region_scores_zero_and_names_its_line(self):
        body = "    #define CHECK(...) ((void)0)\n    (void)s; (void)r; (void)tmin; (void)tmax; (void)rec;\n    return false;"
        text = self.sphere_with(body)
        line = text.split("\n").index("    #define CHECK(...) ((void)0)") + 1
        results = self.run_autograder({SPHERE: text})
        test = self.stage03(results)[0]
        self.assertEqual(test["score"], 0)
        self.assertIn(f"include/rt/intersection/sphere.hpp:{line}:5: expected no preprocessor directive in an exercise region, "
                      f"found #define;", test["output"])

    def test_the_code_of_a_submission_cannot_read_the_reference(self):
        reference = self.root / "source" / "rt" / "include" / "rt" / "shading" / "shading.hpp"
        text = reference.read_text()                               # root reads the reference there
        begin = text.index("RT_EXERCISE_BEGIN(stage05")
        body = [l.strip() for l in text[begin:text.index("RT_EXERCISE_END", begin)].split("\n")[1:]
                if len(l.strip()) > 24 and not l.strip().startswith("//")]
        self.assertTrue(body, "stage 05's region of the reference has no line to look for")
        targets = [reference, self.root / "cache" / "tree" / "tests" / "stage03_sphere.cpp"]
        paths = ", ".join(json.dumps(str(t)) for t in targets)
        attack = (f"    for (const char* path : {{{paths}}}) {{\n"
                  f"        if (std::FILE* f = std::fopen(path, \"r\")) {{\n"
                  f"            char line[160] = {{}};\n"
                  f"            std::fgets(line, sizeof line, f);\n"
                  f"            throw rt::error(std::string(\"LEAKED: \") + line);\n"
                  f"        }}\n"
                  f"    }}\n"
                  f"    (void)s; (void)r; (void)tmin; (void)tmax; (void)rec;\n"
                  f"    return false;")
        results = self.run_autograder({SPHERE: self.sphere_with(attack)})
        output = self.stage03(results)[0]["output"]
        self.assertEqual(self.stage03(results)[0]["score"], 0)
        self.assertRegex(output, r"include/rt/intersection/sphere\.hpp:\d+:\d+: expected .*, found std::(FILE|fopen);")
        self.assertNotIn("LEAKED", json.dumps(results))
        # the server the submission's code was built into holds the kit's stub of stage 05,
        # not the reference's body (tools/grading/tests/test_attacks.py reads with the
        # scanner off)
        self.run_autograder({})
        servers = sorted((self.root / "cache" / "slots").glob("*/server/*/include/rt/shading/shading.hpp"))
        self.assertTrue(servers, "expected the server's sources in the cache's slot")
        for server in servers:
            source = server.read_text()
            self.assertIn("RT_EXERCISE_BEGIN(stage05", source)
            for line in body:
                self.assertNotIn(line, source, f"{server} holds the reference's stage-05 body")

if __name__ == "__main__":
    unittest.main()
