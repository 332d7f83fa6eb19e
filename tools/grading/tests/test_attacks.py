"""The grader's attack suite: submissions written to score more than their code earns, to
lower another's score, or to read the reference or the hidden tests, each graded by the
real grader (stages 03 and 04 of rt, a hidden suite of stage 03) and checked for its
score and for what it leaked.

Every attack sits in stage 03's region (hit_sphere_textbook) and ends as the honest
failing answer does, `return false;`: it may score no more than that answer. Each runs
twice: through the region scanner, and with the scanner switched off (check_body
accepting everything), so that the verdict holds even where the scanner has a gap.
Nothing of the reference's body of the region, and nothing of the hidden suite, may
appear in what the grader writes.

The kinds (issue 51): forged output, exit games, code before main, lexer mismatches,
reading or writing the grader's files, cross-submission interference, budget exhaustion.
Archive tricks: test_batch.py.

Run: python3 ../../tests/run_suite.py test_attacks   (from tools/grading/tests; as root
it uses the test user rtgrader or nobody, as the grader does)
"""

import contextlib
import hashlib
import io
import json
import os
import shutil
import sys
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
TOOLS = HERE.parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(TOOLS / "tests"))
import grade  # noqa: E402
import make_kit  # noqa: E402
from grade_fixture import have_build_tools, private_copy, run_as_arguments, scanner_off, temporary_folder  # noqa: E402

SECRET = "hidden-suite-secret-5c1e9"
HIDDEN_SUITE = f"""// {SECRET}: no submission may read this
#include <doctest/doctest.h>
#include <rt/intersection/sphere.hpp>
TEST_CASE("hidden: a ray from the origin along -z meets the unit sphere at z = -5 at t = 4")
{{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    s.radius = 1;
    rt::hit_record rec;
    const rt::ray r{{rt::vec3(0), rt::vec3(0, 0, -1)}};
    REQUIRE(rt::hit_sphere_textbook(s, r, 0, rt::infinity, rec));
    CHECK(rec.t == doctest::Approx(4)); // {SECRET}
}}
"""
SUMMARY = r'"[doctest] test cases: 1 | 1 passed | 0 failed | 0 skipped\n[doctest] Status: SUCCESS!\n"'
HONEST_FAILING = ["    return false;"]


def sphere_region(text: str):
    """(index of the BEGIN line, index of the END line) of stage 03's region in sphere.hpp."""
    lines = text.split("\n")
    begin = next(k for k, l in enumerate(lines) if "RT_EXERCISE_BEGIN(stage03" in l)
    end = next(k for k in range(begin, len(lines)) if "RT_EXERCISE_END" in lines[k])
    return lines, begin, end


@unittest.skipUnless(have_build_tools(), "needs cmake, ninja and a C++ compiler")
@unittest.skipUnless(sys.platform.startswith("linux"), "the judge confines the student's code with Linux's seccomp")
class Attacks(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = temporary_folder("attacks")
        cls.reference = private_copy(REPO, cls.tmp / "reference")
        hidden = cls.tmp / "hidden"
        hidden.mkdir(mode=0o700)
        (hidden / "stage03_secret.cpp").write_text(HIDDEN_SUITE)
        weights = cls.tmp / "weights.json"
        # limits well above what a correct case takes (stage 04's longest, 3 s on an idle
        # machine), as the suite runs beside other tests: only an attack may reach them
        weights.write_text(json.dumps({"case_timeout_seconds": 15, "stage_timeout_seconds": 60,
                                       "compile_timeout_seconds": 40,
                                       "stages": {"03": {"visible": 10, "hidden": 5}, "04": {"visible": 15}}}))
        cls.cache = cls.tmp / "cache"
        cls.common = ["--reference", str(cls.reference), "--hidden", str(hidden), "--cache", str(cls.cache),
                      "--work", str(cls.tmp / "work"), "--weights", str(weights), "--stages", "3,4"] + run_as_arguments()
        code, log = cls.quiet(["--calibrate"] + cls.common)
        assert code == 0, "the cache could not be made:\n" + log
        cls.sphere = (cls.reference / "include" / "rt" / "intersection" / "sphere.hpp").read_text()
        lines, begin, end = sphere_region(cls.sphere)
        # what may never be seen: the reference's body of the region, line by line
        cls.secrets = [SECRET] + [l.strip() for l in lines[begin + 1:end]
                                  if len(l.strip()) > 24 and not l.strip().startswith("//")]
        cls.count = 0
        cls.baseline = cls.score(HONEST_FAILING)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @staticmethod
    def quiet(argv):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            code = grade.main(argv)
        return code, err.getvalue()

    @classmethod
    def submission(cls, body, name):
        """The reference's include/rt with stage 03's region holding `body` (lines)."""
        folder = cls.tmp / "submissions" / name
        shutil.copytree(cls.reference / "include" / "rt", folder / "include" / "rt")
        lines, begin, end = sphere_region(cls.sphere)
        text = "\n".join(lines[:begin + 1] + body + lines[end:])
        (folder / "include" / "rt" / "intersection" / "sphere.hpp").write_bytes(text.encode("utf-8"))
        return folder

    @classmethod
    def grade(cls, body, scanner=True):
        """(points of stage 03, points of stage 04, everything the grader wrote) for the body."""
        cls.count += 1
        folder = cls.submission(body, f"s{cls.count}")
        out = cls.tmp / f"out{cls.count}"
        with contextlib.ExitStack() as stack:
            if not scanner:
                stack.enter_context(scanner_off())
            code, log = cls.quiet([str(folder), "--out", str(out)] + cls.common)
        assert code == 0, log
        results = json.loads((out / "results.json").read_text())
        points = {3: 0.0, 4: 0.0}
        for t in results["tests"]:
            points[int(t["number"].split(".")[0])] += t["score"]
        written = (out / "results.json").read_text() + (out / "junit.xml").read_text()
        return points[3], points[4], written

    @classmethod
    def score(cls, body, scanner=True):
        return cls.grade(body, scanner)[0]

    def assert_held(self, body, scanner_too=True, builds=True):
        """The attack scores no more than the honest failing answer, with the scanner on and
        off, and leaks nothing. With the scanner off, an attack that `builds` must compile:
        the judge itself, not a compiler error, has to stop it."""
        for scanner in ([True, False] if scanner_too else [False]):
            with self.subTest(scanner=scanner):
                stage03, stage04, written = self.grade(body, scanner)
                if not scanner and builds:
                    self.assertNotIn("Does not compile", written, "the attack did not compile, so it tests nothing")
                self.assertLessEqual(stage03, self.baseline,
                                     f"the attack scored {stage03}, the honest failing answer {self.baseline}")
                self.assertEqual(stage04, 15, "stage 04's correct code lost points to stage 03's attack")
                for secret in self.secrets:
                    self.assertNotIn(secret, written, "the grader's reports show the reference or the hidden suite")

    # ----------------------------------------------------------------------
    def test_the_reference_scores_full_and_the_honest_failing_answer_does_not(self):
        lines, begin, end = sphere_region(self.sphere)
        stage03, stage04, _ = self.grade(lines[begin + 1:end])
        self.assertEqual((stage03, stage04), (15, 15))
        self.assertLess(self.baseline, 15)

    def test_forged_output(self):
        self.assert_held([f"    std::printf({SUMMARY}); std::fflush(stdout);", "    std::puts(\"[doctest] \");"]
                         + HONEST_FAILING)

    def test_exit_games(self):
        for end in ("std::_Exit(0);", "std::exit(0);", "std::quick_exit(0);", "std::abort();",
                    "std::atexit(+[] { std::_Exit(0); });"):
            with self.subTest(end=end):
                self.assert_held([f"    std::printf({SUMMARY}); std::fflush(stdout);", f"    {end}"]
                                 + HONEST_FAILING)

    def test_code_before_main(self):
        # .init_array.NNNNN (a constructor priority), not .init_array itself, which the
        # server's own static constructors hold with other section flags
        self.assert_held([
            "    [[gnu::section(\".init_array.00101\"), gnu::used]] static void (*early)() = +[] {",
            f"        std::printf({SUMMARY}); std::fflush(stdout); std::_Exit(0);",
            "    };",
            "    (void)early;"] + HONEST_FAILING)
        self.assert_held([
            "    [[ /* after [[ */ gnu::section(\".init_array.00101\"), gnu::used]] static void (*early)() = +[] {",
            "        std::_Exit(0);",
            "    };",
            "    (void)early;"] + HONEST_FAILING)

    def test_lexer_mismatches(self):
        # a backslash and a NUL end a comment line: GCC splices the next line into the comment
        # or not, a naive scanner the other way; either way the judge's cases are not the server's
        self.assert_held(["    // a comment \\\0", "#define TEST_CASE(name) static void f()",
                          "    return false;"])
        self.assert_held(["    // a comment \\ ", "    }", "    inline bool cheat() {"] + HONEST_FAILING,
                         builds=False)
        self.assert_held(["    ??=define CHECK(x) ((void)0)", "    %:define REQUIRE(x) ((void)0)"] + HONEST_FAILING,
                         builds=False)   # gnu++17, as the kit builds: trigraphs are off

    def test_reading_the_graders_files(self):
        source = self.reference / "include" / "rt" / "intersection" / "sphere.hpp"
        hidden = self.tmp / "hidden" / "stage03_secret.cpp"
        for path in (source, hidden, self.cache / "judge" / "cases.json"):
            with self.subTest(path=path.name):
                # at compile time
                self.assert_held([f"    asm(\".incbin \\\"{path}\\\"\");"] + HONEST_FAILING, builds=False)
                # at run time, into an exception's message, which the judge prints
                self.assert_held([
                    f"    if (std::FILE* f = std::fopen(\"{path}\", \"rb\")) {{",
                    "        char text[4096] = {0};",
                    "        std::fread(text, 1, sizeof text - 1, f);",
                    "        throw rt::error(text);",
                    "    }"] + HONEST_FAILING, scanner_too=False)

    def test_writing_the_graders_files(self):
        cases = self.cache / "judge" / "cases.json"
        before = hashlib.sha256(cases.read_bytes()).hexdigest()
        self.assert_held([
            f"    if (std::FILE* f = std::fopen(\"{cases}\", \"wb\")) {{ std::fputs(\"{{}}\", f); std::fclose(f); }}",
            f"    std::remove(\"{self.reference / 'include' / 'rt' / 'intersection' / 'sphere.hpp'}\");"] + HONEST_FAILING,
            scanner_too=False)
        self.assertEqual(hashlib.sha256(cases.read_bytes()).hexdigest(), before)
        self.assertTrue((self.reference / "include" / "rt" / "intersection" / "sphere.hpp").is_file())

    @unittest.skipUnless(os.uname().machine == "x86_64", "the attack makes x86-64 system calls")
    def test_cross_submission_interference(self):
        """A batch of two, graded at once: one submission signals every process it can and
        forks; the other, correct, keeps every point."""
        batch = self.tmp / "batch"
        lines, begin, end = sphere_region(self.sphere)
        # the system calls themselves (no header declares kill in a region): kill(-1, SIGKILL),
        # kill(0, SIGKILL), fork()
        evil = self.submission([
            "    for (int k = 0; k < 64; ++k) {",
            "        long r;",
            "        asm volatile(\"syscall\" : \"=a\"(r) : \"a\"(62L), \"D\"(-1L), \"S\"(9L) : \"rcx\", \"r11\", \"memory\");",
            "        asm volatile(\"syscall\" : \"=a\"(r) : \"a\"(62L), \"D\"(0L), \"S\"(9L) : \"rcx\", \"r11\", \"memory\");",
            "        asm volatile(\"syscall\" : \"=a\"(r) : \"a\"(57L) : \"rcx\", \"r11\", \"memory\");",
            "        (void)r;",
            "    }"] + HONEST_FAILING, "evil")
        honest = self.submission(lines[begin + 1:end], "honest")
        batch.mkdir()
        shutil.copytree(evil, batch / "evil")
        shutil.copytree(honest, batch / "honest")
        out = self.tmp / "batch-out"
        with scanner_off():
            code, log = self.quiet(["--batch", str(batch), "--out", str(out), "--jobs", "2"] + self.common)
        self.assertEqual(code, 0, log)
        rows = {r.split(",")[0]: r.split(",") for r in (out / "grades.csv").read_text().splitlines()[1:]}
        header = (out / "grades.csv").read_text().splitlines()[0].split(",")
        total = header.index("total")
        self.assertEqual(float(rows["honest"][total]), 30.0, rows)
        self.assertLessEqual(float(rows["evil"][total]), self.baseline + 15, rows)

    def test_budget_exhaustion(self):
        """A stage that never compiles, or never ends, costs that stage and nothing else, and
        says which limit it reached."""
        bomb = ["    constexpr auto spin = [] { unsigned long x = 0; for (unsigned long k = 0; k < (1ul << 62); ++k)"
                " x += k * k; return x; };",
                "    static_assert(spin() != 1, \"\");"] + HONEST_FAILING
        stage03, stage04, written = self.grade(bomb, scanner=False)
        self.assertEqual((stage03, stage04), (0, 15))
        self.assertTrue("compile time limit" in written or "error" in written, written[:2000])
        hang = ["    for (volatile unsigned long k = 0;; ++k) {}"] + HONEST_FAILING
        stage03, stage04, written = self.grade(hang, scanner=False)
        self.assertEqual((stage03, stage04), (0, 15))
        self.assertIn("time", written)


if __name__ == "__main__":
    unittest.main()
