"""Tests of tools/make_kit.py: marker validation, parameter parsing, stripping, kit writing.

Run: python3 -m unittest discover -s tools/tests -v   (ctest runs it as tools.make_kit)
"""

import contextlib
import io
import os
import re
import shutil
import subprocess
import sys
import tempfile
import textwrap
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))
import make_kit  # noqa: E402


def scan(text, stages=(1, 2, 3), path="f.hpp"):
    errors = []
    regions = make_kit.scan_file(path, textwrap.dedent(text).lstrip("\n"), set(stages), errors)
    return regions, errors


GOOD = """
    #pragma once
    #include <string>

    namespace rt {

    /// Adds two numbers (a comment outside the region stays).
    inline int add(int a, int b)
    {
        // RT_EXERCISE_BEGIN(stage01: add two numbers)
        // Hint: the + operator.
        //   (a second hint line)
        // not a hint: this explains the solution
        return a + b;
        // RT_EXERCISE_END
    }

    struct thing {
        int value = 0;
        int twice(int k) const
        {
            // RT_EXERCISE_BEGIN(stage02: twice)
            return 2 * value * k;
            // RT_EXERCISE_END
        }
    };

    } // namespace rt
"""


class MarkerValidation(unittest.TestCase):
    def assertOneError(self, text, line, *fragments, stages=(1, 2, 3)):
        _, errors = scan(text, stages)
        self.assertEqual(len(errors), 1, errors)
        self.assertTrue(errors[0].startswith(f"f.hpp:{line}:"), errors[0])
        for fragment in fragments:
            self.assertIn(fragment, errors[0])
        self.assertNotIn("\n", errors[0])
        return errors[0]

    def test_good_file_has_two_regions_and_no_error(self):
        regions, errors = scan(GOOD)
        self.assertEqual(errors, [])
        self.assertEqual([(r.stage, r.title, r.begin_line, r.end_line) for r in regions],
                         [(1, "add two numbers", 9, 14), (2, "twice", 21, 23)])
        self.assertEqual(regions[0].function, "add")
        self.assertEqual(regions[0].parameters, [("a", False), ("b", False)])
        self.assertEqual(regions[1].function, "twice")
        self.assertEqual(regions[0].hints, [" Hint: the + operator.", "   (a second hint line)"])

    def test_end_without_begin(self):
        self.assertOneError("""
            inline void f()
            {
                // RT_EXERCISE_END
            }
        """, 3, "no open region")

    def test_begin_without_end(self):
        self.assertOneError("""
            inline void f()
            {
                // RT_EXERCISE_BEGIN(stage01: f)
            }
        """, 3, "RT_EXERCISE_END before the function's closing brace (line 4)")

    def test_begin_without_end_at_end_of_file(self):
        self.assertOneError("""
            inline void f()
            {
                // RT_EXERCISE_BEGIN(stage01: f)
        """, 3, "RT_EXERCISE_END")

    def test_nested_regions(self):
        self.assertOneError("""
            inline int f(int a)
            {
                // RT_EXERCISE_BEGIN(stage01: outer)
                if (a > 0) {
                    // RT_EXERCISE_BEGIN(stage01: inner)
                    return a;
                }
                return 0;
                // RT_EXERCISE_END
            }
        """, 5, "do not nest")

    def test_unknown_stage(self):
        self.assertOneError("""
            inline void f()
            {
                // RT_EXERCISE_BEGIN(stage09: f)
                // RT_EXERCISE_END
            }
        """, 3, "stage 09, which has none", "tests/stage09_<name>.cpp")

    def test_region_outside_a_function_body(self):
        self.assertOneError("""
            namespace rt {
            // RT_EXERCISE_BEGIN(stage01: f)
            inline void f() {}
            // RT_EXERCISE_END
            }
        """, 2, "directly inside a function body", "a namespace")

    def test_region_in_a_class_body(self):
        _, errors = scan("""
            struct s {
                // RT_EXERCISE_BEGIN(stage01: f)
                int x = 0;
                // RT_EXERCISE_END
            };
        """)
        self.assertTrue(errors[0].startswith("f.hpp:2:"), errors)
        self.assertIn("a class body", errors[0])

    def test_region_in_a_nested_block(self):
        self.assertOneError("""
            inline int f(int a)
            {
                if (a) {
                    // RT_EXERCISE_BEGIN(stage01: f)
                    return 1;
                    // RT_EXERCISE_END
                }
                return 0;
            }
        """, 4, "a block inside a function")

    def test_region_in_a_lambda_is_not_a_function_body(self):
        _, errors = scan("""
            inline auto f = [](int a) {
                // RT_EXERCISE_BEGIN(stage01: f)
                return a;
                // RT_EXERCISE_END
            };
        """)
        self.assertTrue(errors and errors[0].startswith("f.hpp:2:"), errors)

    def test_code_before_the_region(self):
        self.assertOneError("""
            inline int f(int a)
            {
                int b = a;
                // RT_EXERCISE_BEGIN(stage01: f)
                return b;
                // RT_EXERCISE_END
            }
        """, 4, "code before it")

    def test_code_after_the_region(self):
        self.assertOneError("""
            inline int f(int a)
            {
                // RT_EXERCISE_BEGIN(stage01: f)
                a += 1;
                // RT_EXERCISE_END
                return a;
            }
        """, 6, "more code in the function body")

    def test_misspelt_marker(self):
        self.assertOneError("""
            inline void f()
            {
                // RT_EXERCISE_BEGN(stage01: f)
            }
        """, 3, "check the spelling")

    def test_marker_without_stage_title(self):
        self.assertOneError("""
            inline void f()
            {
                // RT_EXERCISE_BEGIN(stage1 f)
            }
        """, 3, "RT_EXERCISE_BEGIN(stageNN: short title)")

    def test_marker_after_code_on_its_line(self):
        _, errors = scan("""
            inline int f()
            {
                return 1; // RT_EXERCISE_END
            }
        """)
        self.assertTrue(any(e.startswith("f.hpp:3:") and "alone on its line" in e for e in errors), errors)

    def test_marker_in_a_block_comment(self):
        _, errors = scan("""
            inline void f()
            {
                /* RT_EXERCISE_BEGIN(stage01: f) */
            }
        """)
        self.assertTrue(errors and errors[0].startswith("f.hpp:3:") and "/* */" in errors[0], errors)

    def test_noexcept_and_constexpr_are_refused(self):
        _, errors = scan("""
            inline int f(int a) noexcept
            {
                // RT_EXERCISE_BEGIN(stage01: f)
                return a;
                // RT_EXERCISE_END
            }
            constexpr int g(int a)
            {
                // RT_EXERCISE_BEGIN(stage01: g)
                return a;
                // RT_EXERCISE_END
            }
        """)
        self.assertEqual(len(errors), 2, errors)
        self.assertIn("noexcept", errors[0])
        self.assertIn("constexpr", errors[1])

    def test_two_regions_in_one_body(self):
        self.assertOneError("""
            inline int f(int a)
            {
                // RT_EXERCISE_BEGIN(stage01: f)
                // RT_EXERCISE_END
                // RT_EXERCISE_BEGIN(stage01: g)
                return a;
                // RT_EXERCISE_END
            }
        """, 5, "one region per function body")

    def test_strings_comments_and_braces_in_them_do_not_confuse_the_scanner(self):
        regions, errors = scan(r'''
            #define BRACE {
            inline const char* f(char c)
            {
                // RT_EXERCISE_BEGIN(stage01: f)
                /* } */ const char* s = "}{ \" RT_EXERCISE_END";
                const char* raw = R"x( } // RT_EXERCISE_END )x";
                (void)raw;
                return c == '}' ? s : "{";
                // RT_EXERCISE_END
            }
            const int million = 1'000'000;
            inline int g(int a)
            {
                // RT_EXERCISE_BEGIN(stage02: g)
                return a + million;
                // RT_EXERCISE_END
            }
        ''')
        self.assertEqual(errors, [])
        self.assertEqual([(r.function, r.begin_line, r.end_line) for r in regions], [("f", 4, 9), ("g", 14, 16)])

    def test_every_error_of_a_file_is_reported(self):
        _, errors = scan("""
            inline void f()
            {
                // RT_EXERCISE_END
            }
            inline void g()
            {
                // RT_EXERCISE_BEGIN(stage07: g)
                // RT_EXERCISE_END
            }
        """)
        self.assertEqual(len(errors), 2, errors)


class Parameters(unittest.TestCase):
    def params(self, signature):
        return make_kit.parse_parameters(signature)

    def test_signatures(self):
        cases = {
            "inline bool hit(const sphere& s, const ray& r, real tmin, real tmax, hit_record& rec)":
                [("s", False), ("r", False), ("tmin", False), ("tmax", False), ("rec", False)],
            "inline void write(std::ostream& out, const image& img, float gamma = 2.2f)":
                [("out", False), ("img", False), ("gamma", False)],
            "int f()": [],
            "int f(void)": [],
            "int f(int, const sphere&, std::size_t, unsigned int)": [],
            "int f(const std::map<int, std::pair<int, int>>& m, int n = std::max(1, 2))":
                [("m", False), ("n", False)],
            "template <class... Args> void f(Args&&... args)": [("args", True)],
            "void f(int a[3], void (*callback)(int), double (&row)[4])":
                [("a", False), ("callback", False), ("row", False)],
            "bool operator()(const ray& r) const": [("r", False)],
            "auto f(int x) -> decltype(x + 1)": [("x", False)],
            "int f(const window w = window{}, bool flag = a <= b)": [("w", False), ("flag", False)],
        }
        for signature, expected in cases.items():
            with self.subTest(signature=signature):
                self.assertEqual(self.params(make_kit._strip_template_prefix(signature)), expected)

    def test_constructor_with_an_initializer_list(self):
        regions, errors = scan("""
            struct box {
                int lo, hi;
                box(int a, int b) : lo{a}, hi(b)
                {
                    // RT_EXERCISE_BEGIN(stage01: box)
                    if (lo > hi) { int t = lo; lo = hi; hi = t; }
                    // RT_EXERCISE_END
                }
            };
        """)
        self.assertEqual(errors, [])
        self.assertEqual(regions[0].parameters, [("a", False), ("b", False)])


class Stripping(unittest.TestCase):
    def strip(self, text, stages=(1, 2)):
        text = textwrap.dedent(text).lstrip("\n")
        regions, errors = scan(text, (1, 2, 3), path="include/rt/f.hpp")
        self.assertEqual(errors, [])
        chosen = [r for r in regions if r.stage in stages]
        return make_kit.strip_text("include/rt/f.hpp", text, chosen,
                                   {1: "docs/stages/01-first.md", 2: None}), text

    def test_signature_comments_and_markers_are_kept(self):
        out, original = self.strip(GOOD)
        for line in ("/// Adds two numbers (a comment outside the region stays).",
                     "inline int add(int a, int b)", "int twice(int k) const",
                     "    // RT_EXERCISE_BEGIN(stage01: add two numbers)", "    // RT_EXERCISE_END",
                     "        // RT_EXERCISE_BEGIN(stage02: twice)"):
            self.assertIn(line + "\n", out)
        self.assertNotIn("return a + b;", out)
        self.assertNotIn("return 2 * value * k;", out)
        self.assertNotIn("not a hint", out)

    def test_the_body_throws_the_not_done_message_with_a_todo_and_the_hints(self):
        out, _ = self.strip(GOOD)
        expected = textwrap.dedent("""\
            {
                // RT_EXERCISE_BEGIN(stage01: add two numbers)
                // TODO(stage 01): add two numbers; see docs/stages/01-first.md.
                // Hint: the + operator.
                //   (a second hint line)
                (void)a;
                (void)b;
                throw rt::exercise_not_done("stage 01: add two numbers: see docs/stages/01-first.md");
                // RT_EXERCISE_END
            }
        """)
        self.assertIn(expected, out)
        # a stage without a doc page points to the student guide
        self.assertIn('throw rt::exercise_not_done("stage 02: twice: see docs/student-guide.md");', out)

    def test_error_header_is_included_once(self):
        out, _ = self.strip(GOOD)
        self.assertEqual(out.count('#include "core/error.hpp"'), 1)
        lines = out.splitlines()
        self.assertEqual(lines.index('#include "core/error.hpp" // rt::exercise_not_done (student kit)'),
                         lines.index("#include <string>") + 1)
        already = GOOD.replace("#include <string>", '#include <string>\n    #include "error.hpp"')
        out2, _ = self.strip(already)
        self.assertEqual(out2.count("error.hpp"), 1)

    def test_only_the_chosen_stages_are_stripped(self):
        out, _ = self.strip(GOOD, stages=(2,))
        self.assertIn("return a + b;", out)
        self.assertNotIn("return 2 * value * k;", out)

    def test_stripping_twice_changes_nothing(self):
        once, _ = self.strip(GOOD)
        regions, errors = scan(once, path="include/rt/f.hpp")
        self.assertEqual(errors, [])
        twice = make_kit.strip_text("include/rt/f.hpp", once, regions, {1: "docs/stages/01-first.md", 2: None})
        self.assertEqual(once, twice)

    def test_a_region_that_repeats_an_earlier_stage_is_stripped_with_it(self):
        text = GOOD.replace("RT_EXERCISE_BEGIN(stage02: twice)", "RT_EXERCISE_BEGIN(stage02: twice; repeats stage01)")
        regions, errors = scan(text)
        self.assertEqual(errors, [])
        twice = next(r for r in regions if r.stage == 2)
        self.assertEqual(twice.title, "twice")
        self.assertEqual(twice.repeats, [1])
        self.assertTrue(twice.strips_with({1}))   # stripping stage 01 strips it too
        self.assertTrue(twice.strips_with({2}))
        self.assertFalse(twice.strips_with({3}))
        add = next(r for r in regions if r.stage == 1)
        self.assertFalse(add.strips_with({2}))    # not the other way round

    def test_repeats_must_name_an_earlier_known_stage(self):
        for wrong in ("repeats stage02", "repeats stage03", "repeats stage07"):
            text = GOOD.replace("RT_EXERCISE_BEGIN(stage02: twice)", f"RT_EXERCISE_BEGIN(stage02: twice; {wrong})")
            _, errors = scan(text)
            self.assertEqual(len(errors), 1, errors)
            self.assertIn("an earlier stage with a test suite after 'repeats'", errors[0])

    def test_a_title_with_quotes_is_escaped(self):
        region = make_kit.Region("f.hpp", 3, 'the "best" \\ way', 1, 2, "", "f", [])
        self.assertIn(r'"stage 03: the \"best\" \\ way: see docs/student-guide.md"',
                      make_kit.stripped_body(region, None)[-1])


@unittest.skipUnless(shutil.which("g++") or shutil.which("clang++"), "no C++ compiler")
class StrippedBodiesCompile(unittest.TestCase):
    """The throwing bodies compile warning-free under -Wall -Wextra -Wpedantic -Werror."""

    SOURCE = """
        #pragma once
        #include <string>
        #include <utility>
        #include <vector>

        namespace rt {
        struct point { double x = 0, y = 0; };

        inline double length(const point& p, double scale = 1.0)
        {
            // RT_EXERCISE_BEGIN(stage01: length)
            return scale * (p.x + p.y);
            // RT_EXERCISE_END
        }

        inline void fill(std::vector<int>& out, int, const int* first, std::size_t count)
        {
            // RT_EXERCISE_BEGIN(stage01: fill)
            out.assign(first, first + count);
            // RT_EXERCISE_END
        }

        template <class T, class... Rest>
        T first_of(T value, Rest&&... rest)
        {
            // RT_EXERCISE_BEGIN(stage02: first)
            (void)sizeof...(rest);
            return value;
            // RT_EXERCISE_END
        }

        struct counter {
            int n = 0;
            counter(int start, int step) : n{start * step}
            {
                // RT_EXERCISE_BEGIN(stage02: counter)
                n += 1;
                // RT_EXERCISE_END
            }
            std::string name(int width) const
            {
                // RT_EXERCISE_BEGIN(stage02: name)
                return std::string(std::size_t(width), 'x');
                // RT_EXERCISE_END
            }
            point operator()(const point& p) const
            {
                // RT_EXERCISE_BEGIN(stage02: call)
                return p;
                // RT_EXERCISE_END
            }
        };
        } // namespace rt
    """

    def test_stripped_fixture_compiles_with_each_compiler(self):
        text = textwrap.dedent(self.SOURCE).lstrip("\n")
        regions, errors = scan(text, path="include/rt/fixture.hpp")
        self.assertEqual(errors, [])
        self.assertEqual(len(regions), 6)
        stripped = make_kit.strip_text("include/rt/fixture.hpp", text, regions, {})
        with tempfile.TemporaryDirectory() as tmp:
            rt_dir = Path(tmp, "include", "rt")
            (rt_dir / "core").mkdir(parents=True)
            shutil.copy(REPO / "include" / "rt" / "core" / "error.hpp", rt_dir / "core" / "error.hpp")
            (rt_dir / "fixture.hpp").write_text(stripped)
            main = Path(tmp, "use.cpp")
            main.write_text('#include <rt/fixture.hpp>\nint main() {\n  rt::counter c(1, 2);\n'
                            '  return int(rt::length({}) + rt::first_of(1, 2.0) + c.n);\n}\n')
            for compiler in ("g++", "clang++"):
                if not shutil.which(compiler):
                    continue
                with self.subTest(compiler=compiler):
                    p = subprocess.run([compiler, "-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror",
                                        "-fsyntax-only", "-I", str(Path(tmp, "include")), str(main)],
                                       capture_output=True, text=True)
                    self.assertEqual(p.returncode, 0, p.stderr)


class SwitchableKit(unittest.TestCase):
    """check_kit's switchable kit: every body kept, thrown past only for the stages RT_KIT_STRIP names."""

    def test_the_switchable_fixture_builds_and_strips_only_the_chosen_stages(self):
        text = textwrap.dedent(StrippedBodiesCompile.SOURCE).lstrip("\n")
        regions, errors = scan(text, path="include/rt/fixture.hpp")
        self.assertEqual(errors, [])
        regions[0].repeats = [2]  # "length" repeats a stage-02 answer: stripped with stage 02 too
        switched = make_kit.switchable_text("include/rt/fixture.hpp", text, regions, {})
        self.assertIn("if (rt::detail::kit_check_strips({1, 2})) {", switched)
        self.assertIn("return scale * (p.x + p.y);", switched)  # the reference body stays
        compiler = shutil.which("g++") or shutil.which("clang++")
        if compiler is None:
            self.skipTest("no C++ compiler")
        with tempfile.TemporaryDirectory() as tmp:
            rt_dir = Path(tmp, "include", "rt")
            (rt_dir / "core").mkdir(parents=True)
            (rt_dir / "core" / "error.hpp").write_text((REPO / "include" / "rt" / "core" / "error.hpp").read_text() +
                                              make_kit.KIT_CHECK_SWITCH)
            (rt_dir / "fixture.hpp").write_text(switched)
            main = Path(tmp, "use.cpp")
            main.write_text('#include <cstdio>\n#include <rt/fixture.hpp>\nint main() {\n  try {\n'
                            '    const double l = rt::length({});\n    rt::counter c(1, 2);\n'
                            '    return int(l + rt::first_of(1, 2.0) + c.n) == 4 ? 0 : 1;\n'
                            '  } catch (const rt::exercise_not_done& e) {\n'
                            '    std::puts(e.what());\n    return 3;\n  }\n}\n')
            exe = Path(tmp, "use")
            p = subprocess.run([compiler, "-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror",
                                "-I", str(Path(tmp, "include")), str(main), "-o", str(exe)],
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)
            for strip, code, message in [("", 0, ""), ("7", 0, ""), ("1", 3, "stage 01: length"),
                                         ("2", 3, "stage 01: length"), ("3,2", 3, "stage 01: length")]:
                with self.subTest(RT_KIT_STRIP=strip):
                    run = subprocess.run([str(exe)], capture_output=True, text=True,
                                         env=dict(os.environ, RT_KIT_STRIP=strip))
                    self.assertEqual(run.returncode, code, run.stdout)
                    self.assertIn(message, run.stdout)
            # without the repeat, stage 02 strips only its own: the counter's constructor
            regions[0].repeats = []
            switched = make_kit.switchable_text("include/rt/fixture.hpp", text, regions, {})
            (rt_dir / "fixture.hpp").write_text(switched)
            p = subprocess.run([compiler, "-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror",
                                "-I", str(Path(tmp, "include")), str(main), "-o", str(exe)],
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)
            run = subprocess.run([str(exe)], capture_output=True, text=True, env=dict(os.environ, RT_KIT_STRIP="2"))
            self.assertEqual((run.returncode, run.stdout.strip()), (3, "stage 02: counter: see docs/student-guide.md"))


class Kits(unittest.TestCase):
    """Kits written from a small repository made here."""

    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="make-kit-test-"))
        self.repo = self.tmp / "repo"
        files = {
            "include/rt/a.hpp": GOOD,
            "include/rt/core/error.hpp": "#pragma once\n",
            "tests/stage01_one.cpp": "// one\n",
            "tests/stage02_two.cpp": "// two\n",
            "tests/hidden/stage01_secret.cpp": "// hidden\n",
            "tests/data/x.txt": "data\n",
            "docs/stages/01-first.md": "# one\n",
            "tools/grade.py": "# grader\n",
            "tools/kit_manifest.json": '{"exercise_roots": ["include"], '
                                       '"instructor_only": ["tests/hidden/", "tools/grade.py", "*.secret", "tools/kit/"]}',
            "notes.secret": "answers\n",
            "README.md": "the reference solution and its tools\n",
            "DEVELOPERS.md": "the reference solution; tools/check_kit.py\n",
            "tools/kit/README.md": "your kit\n",
            "tools/kit/DEVELOPERS.md": "your code\n",
            ".ci/run": "python3 tools/check_kit.py\n",
            "tools/kit/ci-run": "stages=(@RT_KIT_STAGES@)\n",
            "build/CMakeCache.txt": "junk\n",
        }
        for rel, text in files.items():
            path = self.repo / rel
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(textwrap.dedent(text).lstrip("\n"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def make(self, *args):
        return make_kit.main(["--source", str(self.repo), *args])

    def make_printing(self, *args):
        """(exit code, stdout, stderr) of make_kit; a refusal by argparse is exit code 2."""
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = self.make(*args)
            except SystemExit as e:
                code = e.code
        return code, out.getvalue(), err.getvalue()

    def test_from_stage_strips_later_stages_and_leaves_instructor_material_out(self):
        kit = self.tmp / "kit"
        self.assertEqual(self.make("--from-stage", "2", str(kit)), 0)
        text = (kit / "include/rt/a.hpp").read_text()
        self.assertIn("return a + b;", text)  # stage 01 solved
        self.assertIn('throw rt::exercise_not_done("stage 02: twice: see docs/student-guide.md");', text)
        for absent in ("tests/hidden/stage01_secret.cpp", "tools/grade.py", "notes.secret", "build"):
            self.assertFalse((kit / absent).exists(), absent)
        for present in ("tests/stage01_one.cpp", "tests/data/x.txt", "docs/stages/01-first.md",
                        "tools/kit_manifest.json"):
            self.assertTrue((kit / present).is_file(), present)
        self.assertEqual([p.name for p in self.tmp.iterdir() if ".tmp-" in p.name], [])

    def test_the_kit_readme_and_developers_guide_are_the_students(self):
        kit = self.tmp / "kit"
        self.assertEqual(self.make("--from-stage", "1", str(kit)), 0)
        self.assertEqual((kit / "README.md").read_text(), "your kit\n")
        self.assertEqual((kit / "DEVELOPERS.md").read_text(), "your code\n")
        self.assertFalse((kit / "tools/kit").exists())

    def test_the_kit_ci_runs_the_stripped_stages_not_the_reference_ci(self):
        # .ci/ is a dot folder: a kit takes it from git's list of the repository's files
        if shutil.which("git") is None:
            self.skipTest("needs git")
        subprocess.run(["git", "init", "-q", str(self.repo)], check=True)
        kit = self.tmp / "kit"
        self.assertEqual(self.make("--from-stage", "2", str(kit)), 0)
        self.assertEqual((kit / ".ci/run").read_text(), "stages=(02)\n")
        kit = self.tmp / "kitall"
        self.assertEqual(self.make("--all", str(kit)), 0)
        self.assertEqual((kit / ".ci/run").read_text(), "stages=(01 02)\n")

    def test_all_strips_every_stage(self):
        kit = self.tmp / "kitall"
        self.assertEqual(self.make("--all", str(kit)), 0)
        self.assertEqual((kit / "include/rt/a.hpp").read_text().count("throw rt::exercise_not_done"), 2)

    def test_a_kit_says_which_answers_it_gives_away(self):
        code, out, _ = self.make_printing("--from-stage", "2", str(self.tmp / "kit2"))
        self.assertEqual(code, 0)
        self.assertIn("gives away the answers of stage 01 (1 region): a kit from stage 02 hands out the earlier "
                      "stages solved", out)
        code, out, _ = self.make_printing("--all", str(self.tmp / "kitall"))
        self.assertEqual(code, 0)
        self.assertIn("gives away no answer", out)

    def test_no_kit_strips_a_stage_and_hands_out_a_later_one_solved(self):
        # --only-stage N would strip N alone and hand out the later stages solved: it is refused,
        # naming the option that strips N and every later stage
        code, _, err = self.make_printing("--only-stage", "1", str(self.tmp / "kit1"))
        self.assertEqual(code, 2)
        self.assertIn("--from-stage 1", err)
        self.assertFalse((self.tmp / "kit1").exists())
        for first in (1, 2):
            stripped = make_kit.select_stages([1, 2], first, False)
            self.assertEqual(stripped, {s for s in (1, 2) if s >= first})

    def test_an_existing_target_needs_force(self):
        kit = self.tmp / "kit"
        kit.mkdir()
        (kit / "old.txt").write_text("old")
        self.assertEqual(self.make("--all", str(kit)), 2)
        self.assertTrue((kit / "old.txt").exists())
        self.assertEqual(self.make("--all", "--force", str(kit)), 0)
        self.assertFalse((kit / "old.txt").exists())

    def test_a_target_inside_the_repository_is_refused(self):
        self.assertEqual(self.make("--all", str(self.repo / "kit")), 2)
        self.assertFalse((self.repo / "kit").exists())

    def test_a_stage_beyond_the_last_is_refused(self):
        # a kit from stage 05 of a two-stage course would strip nothing and hand out every answer
        code, _, err = self.make_printing("--from-stage", "5", str(self.tmp / "kit"))
        self.assertEqual(code, 2)
        self.assertIn("expected a stage up to 02", err)
        self.assertFalse((self.tmp / "kit").exists())

    def test_marker_errors_stop_the_kit(self):
        (self.repo / "include/rt/bad.hpp").write_text("inline void f()\n{\n    // RT_EXERCISE_END\n}\n")
        self.assertEqual(self.make("--all", str(self.tmp / "kit")), 2)
        self.assertFalse((self.tmp / "kit").exists())
        self.assertEqual(self.make("--check"), 2)

    def test_sync_rewrites_only_what_changed(self):
        kit = self.tmp / "kit"
        plan = make_kit.plan_kit(self.repo, {1, 2})
        self.assertEqual(make_kit.sync_kit(self.repo, plan, kit), len(plan.files))
        (kit / "stale.txt").write_text("stale")
        plan = make_kit.plan_kit(self.repo, {2})
        self.assertEqual(make_kit.sync_kit(self.repo, plan, kit), 1)  # only a.hpp changes
        self.assertFalse((kit / "stale.txt").exists())
        self.assertIn("return a + b;", (kit / "include/rt/a.hpp").read_text())


class TheRepositorysKit(unittest.TestCase):
    """A kit of this repository, as a course hands it out in week 3."""

    def test_its_ci_script_builds_the_stripped_stages_and_needs_nothing_the_kit_lacks(self):
        with tempfile.TemporaryDirectory() as tmp:
            kit = Path(tmp) / "kit"
            with contextlib.redirect_stdout(io.StringIO()):
                self.assertEqual(make_kit.main(["--from-stage", "3", str(kit)]), 0)
            script = (kit / ".ci" / "run").read_text()
            self.assertIn("stages=(03 04 05 06 07 08 09 10 11)", script)
            self.assertIn('--target "check_stage$stage"', script)
            self.assertIn("-L '^library$'", script)
            for path in set(re.findall(r"\b(?:tools|tests|scripts)/[\w./-]+", script)):
                self.assertTrue((kit / path).exists(), f".ci/run names {path}, which the kit does not hold")
            if shutil.which("bash"):
                p = subprocess.run(["bash", "-n", str(kit / ".ci" / "run")], capture_output=True, text=True)
                self.assertEqual(p.returncode, 0, p.stderr)
            self.assertTrue(os.access(kit / ".ci" / "run", os.X_OK))


if __name__ == "__main__":
    unittest.main()
