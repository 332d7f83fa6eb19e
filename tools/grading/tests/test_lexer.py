"""Tests of the region scanner: tools/grading/lexer.py (a region's bytes read as the compiler
reads them), region_check.py and names.py (what a region may name), through
splice.check_body, the one entry point the grader calls. Each refusal is checked for its
line and column in the student's file and for what it names; every region body of the
reference, every kit stub and every planted honest mistake must be accepted.

Run: python3 -m unittest discover -s tools/grading/tests -p 'test_lexer.py'
(ctest runs it as tools.grading.lexer)
"""

import re
import sys
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
TOOLS = HERE.parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))
import make_kit  # noqa: E402
import planted_mistakes  # noqa: E402
from grading import lexer, splice  # noqa: E402

FX = "include/rt/fx.hpp"
ONE_LINE = re.compile(r"^include/rt/[\w./]+\.hpp:\d+:\d+: expected [^\n]+, found [^\n]+; [^\n]+$")


def check(*lines: str, rel: str = FX, first: int = 10) -> str:
    return splice.check_body(rel, first, list(lines))


class Case(unittest.TestCase):
    def refused(self, lines, where, *fragments, rel=FX):
        """The region is refused at `where` ("line:col") with a message holding `fragments`."""
        message = check(*lines, rel=rel)
        self.assertRegex(message, ONE_LINE)
        self.assertTrue(message.startswith(f"{rel}:{where}: "), message)
        for fragment in fragments:
            self.assertIn(fragment, message)
        return message

    def accepted(self, *lines, rel=FX):
        self.assertEqual(check(*lines, rel=rel), "")


class Bytes(Case):
    """Phase 1: only printable characters, tabs and line ends."""

    def test_control_bytes_are_refused_by_their_value(self):
        for byte in (0x00, 0x01, 0x08, 0x0B, 0x0C, 0x0D, 0x1B, 0x7F):
            with self.subTest(byte=byte):
                self.refused(["    int x = 1;", f"    return x;{chr(byte)} // after"], "11:14",
                             f"found a control byte 0x{byte:02X}")

    def test_a_tab_is_fine(self):
        self.accepted("\tint x = 1;\t// a tab", "\treturn x;")

    def test_c1_controls_and_bidirectional_overrides_are_refused_even_in_comments(self):
        self.refused(["    return 1; // \u0085"], "10:18", "a control character U+0085")
        self.refused(["    return 1; // \u202e } \u2066"], "10:18", "a bidirectional-text control U+202E")

    def test_a_byte_that_is_not_utf8_is_refused_by_its_value(self):
        text = b"inline int f()\n{\n    // RT_EXERCISE_BEGIN(stage01: f)\n    return 1; // caf\xe9\n" \
               b"    // RT_EXERCISE_END\n}\n"
        student = splice.read_student_file(FX, text.decode("utf-8", errors="surrogateescape"))
        problem = student.regions[(1, "f")].problem
        self.assertRegex(problem, ONE_LINE)
        self.assertTrue(problem.startswith(f"{FX}:4:21: "), problem)
        self.assertIn("found a byte 0xE9 that is not UTF-8", problem)

    def test_non_ascii_in_comments_and_strings_is_fine(self):
        self.accepted("    // déjà vu: ∂x/∂t", "    const char* s = \"naïve\";", "    return s[0];")


class LineEnds(Case):
    def test_line_numbers_follow_crlf_and_a_lone_cr_as_the_compiler_does(self):
        text = "inline int f()\r\n{\r\n    // RT_EXERCISE_BEGIN(stage01: f)\r    int x = 1;\r\n" \
               "    #define X\r\n    // RT_EXERCISE_END\n}\n"
        student = splice.read_student_file(FX, text)
        self.assertTrue(student.regions[(1, "f")].problem.startswith(f"{FX}:5:5: expected no preprocessor"))


class Splices(Case):
    """Phase 2: a backslash before a line end joins two lines, wherever it stands."""

    def test_a_backslash_at_the_end_of_a_line(self):
        self.refused(["    int x = 1; \\", "    return x;"], "10:16", "expected no backslash at the end of a line")

    def test_gccs_splice_with_spaces_tabs_and_a_nul_after_the_backslash(self):
        self.refused(["    int x = 1; \\ \t \0", "    return x;"], "10:16", "a line splice")

    def test_at_the_end_of_a_line_comment(self):
        self.refused(["    return 1; // a comment \\", "    }", "    inline bool cheat() {"], "10:28",
                     "a backslash there")

    def test_inside_a_string_and_after_an_escaped_backslash(self):
        self.refused(["    const char* s = \"a\\", "b\";"], "10:23", "a line splice")
        self.refused(["    const char* s = \"a\\\\\\", "\";"], "10:25", "a line splice")

    def test_at_the_end_of_the_region(self):
        self.refused(["    return 1; // \\"], "10:18", "a line splice")

    def test_the_trigraph_for_a_backslash(self):
        self.refused(["    return 1; // ??/", "    }"], "10:18", "??/ (a trigraph for a backslash)")


class Trigraphs(Case):
    def test_a_trigraph_outside_a_comment_is_refused_with_what_it_stands_for(self):
        self.refused(["    ??=define CHECK(x) ((void)0)"], "10:5", "found ??= (a trigraph for #)")
        self.refused(["    return \"what??!\";"], "10:17", "found ??! (a trigraph for |)")
        self.refused(["    return \"\\??/\";"], "10:14", "found ??/")

    def test_in_a_comment_only_the_backslash_one_matters(self):
        self.accepted("    // what??! fine ??= here", "    return 1;")

    def test_question_marks_that_are_no_trigraph(self):
        self.accepted("    return \"?\\?=\"[0] == '?' ? a ? 1 : 2 : 0;")


class Tokens(unittest.TestCase):
    def test_positions_are_the_students_lines_and_columns(self):
        toks = lexer.tokens("  int x;\n\treturn x;", 41)
        self.assertEqual([(t.text, t.line, t.column) for t in toks],
                         [("int", 41, 3), ("x", 41, 7), (";", 41, 8), ("return", 42, 2), ("x", 42, 9),
                          (";", 42, 10)])

    def test_digraphs_and_alternative_tokens_mean_their_symbols(self):
        toks = lexer.tokens("v<:0:> = <%1%>; a and not b; x <::y; z<:::w; q<::>")
        self.assertEqual([t.text for t in toks],
                         ["v", "[", "0", "]", "=", "{", "1", "}", ";", "a", "&&", "!", "b", ";", "x", "<", "::",
                          "y", ";", "z", "[", "::", "w", ";", "q", "[", "]"])

    def test_pp_numbers_literals_and_raw_strings(self):
        toks = lexer.tokens("1'000 0x1p-3 1.5e+10f .5 u8\"s\" L'c' R\"d(a)\" )d\" uR\"(x)\"")
        self.assertEqual([(t.kind, t.text) for t in toks],
                         [("number", "1'000"), ("number", "0x1p-3"), ("number", "1.5e+10f"), ("number", ".5"),
                          ("string", "u8\"s\""), ("char", "L'c'"), ("string", "R\"d(a)\" )d\""),
                          ("string", "uR\"(x)\"")])


class Phase3(Case):
    def test_directives_in_every_spelling(self):
        self.refused(["    int x = 1;", "    #define CHECK(...) ((void)0)"], "11:5",
                     "expected no preprocessor directive in an exercise region, found #define")
        self.refused(["  /**/ #include </etc/passwd>"], "10:8", "found #include")
        self.refused(["  %:undef CHECK"], "10:3", "found #undef")
        self.refused(["  return 1; %:%: x"], "10:13", "preprocessor directive")

    def test_comments_and_literals_that_stay_open(self):
        self.refused(["    return 0; /* the rest of the file"], "10:15", "expected */ closing this comment")
        self.refused(["    const char* s = \"open;"], "10:21", "expected the string closed on its line")
        self.refused(["    char c = 'x;"], "10:14", "expected the character literal closed on its line")

    def test_raw_strings(self):
        self.accepted("    auto s = R\"x(", "  } #define )\" \"", ")x\";", "    return s.size();")
        self.accepted("    auto s = R\"x()\" )\" )x\"; return s;")
        self.refused(["    auto s = R\"x(never closed )\" ", "    return 0;"], "10:14",
                     "expected the raw string closed inside the region", ")x\"")
        self.refused(["    auto s = R\"abcdefghijklmnopq(x)abcdefghijklmnopq\";"], "10:14", "at most 16 characters")
        self.refused(["    auto s = R\"a b(x)a b\";"], "10:14", "no space")

    def test_universal_character_names_and_non_ascii_names(self):
        self.refused(["    int caf\\u00e9 = 1;"], "10:12", "a universal character name \\u00e9")
        self.refused(["    int \\u0063 = 1;"], "10:9", "a universal character name")
        self.refused(["    int café = 1;"], "10:12", "U+00E9", "ASCII")
        self.refused(["    int a$b = 1;"], "10:10", "'$'")

    def test_user_defined_literals(self):
        self.refused(["    return \"x\"_s;"], "10:15", "a user-defined literal suffix _s")

    def test_brackets(self):
        self.refused(["    return 0;", "}", "int evil() {"], "11:1",
                     "expected code that stays inside the function body, found an unmatched '}'")
        self.refused(["    return 0;", "%>"], "11:1", "an unmatched '%>'")
        self.refused(["    if (a) {", "        return b;"], "10:12", "expected '}' for this '{'")
        self.refused(["    return f(a];"], "10:15", "expected a bracket closing the '(' of line 10")


class Names(Case):
    """The allow-list: every attack names something the lists leave out."""

    ATTACKS = {
        "auto f = fopen;": ("10:10", "found fopen"),
        "decltype(fopen) x;": ("10:10", "found fopen"),
        "(fopen)(\"/etc/passwd\", \"r\");": ("10:2", "found fopen"),
        "auto p = &::fopen;": ("10:11", "found ::fopen"),
        "using namespace std; printf(\"x\");": ("10:1", "found using namespace std"),
        "using std::fopen;": ("10:1", "found using std"),
        "namespace s = std;": ("10:1", "found namespace"),
        "std::string s; getline(in, s);": ("10:16", "found getline"),
        "std::system(\"id\");": ("10:1", "found std::system"),
        "std::getenv(\"HOME\");": ("10:1", "found std::getenv"),
        "std::exit(0);": ("10:1", "found std::exit"),
        "std::_Exit(0);": ("10:1", "found std::_Exit"),
        "std::quick_exit(0);": ("10:1", "found std::quick_exit"),
        "std::atexit(nullptr);": ("10:1", "found std::atexit"),
        "std::abort();": ("10:1", "found std::abort"),
        "std::signal(9, nullptr);": ("10:1", "found std::signal"),
        "std::raise(9);": ("10:1", "found std::raise"),
        "std::printf(\"[doctest] ok\");": ("10:1", "found std::printf"),
        "std::cout << 1;": ("10:1", "found std::cout"),
        "std::fopen(\"x\", \"r\");": ("10:1", "found std::fopen"),
        "std::ofstream f(\"x\");": ("10:1", "found std::ofstream"),
        "std::thread t;": ("10:1", "found std::thread"),
        "std::remove(\"x\");": ("10:1", "found std::remove"),
        "kill(-1, 9);": ("10:1", "found kill"),
        "fork();": ("10:1", "found fork"),
        "syscall(62, -1, 9);": ("10:1", "found syscall"),
        "write(1, \"x\", 1);": ("10:1", "found write"),
        "open(\"x\", 0);": ("10:1", "found open"),
        "main();": ("10:1", "found main"),
        "char** e = environ;": ("10:12", "found environ"),
        "rt::load_scene(\"x.scene\");": ("10:1", "found rt::load_scene"),
        "rt::load_scene_from_string(\"mesh x.obj\");": ("10:1", "found rt::load_scene_from_string"),
        "detail::open_for_reading(\"x\");": ("10:1", "found detail::open_for_reading"),
        "glm::detail::compute_dot<int>();": ("10:1", "found glm::detail"),
        "__builtin_trap();": ("10:1", "not reserved to the compiler, found __builtin_trap"),
        "return __FILE__;": ("10:8", "found __FILE__"),
        "doctest::detail::g_cs = nullptr;": ("10:1", "expected no use of the test framework"),
        "CHECK(true);": ("10:1", "expected no use of the test framework"),
    }

    def test_each_attack_is_refused_by_name_where_it_stands(self):
        for line, (where, fragment) in self.ATTACKS.items():
            with self.subTest(line=line):
                self.refused([line], where, fragment)

    def test_each_refusal_tells_an_honest_student_what_to_do(self):
        self.assertIn("return the result; do not print it", check("std::printf(\"x\");"))
        self.assertIn("may not end, start or signal a process", check("std::exit(0);"))
        self.assertIn("computes from its arguments only", check("std::getenv(\"x\");"))
        self.assertIn("<cmath>, <algorithm>", check("std::map<int, int> m;"))

    def test_the_vetted_names_are_accepted(self):
        self.accepted("const real r = std::sqrt(std::max(real(0), std::fabs(a)));",
                      "std::vector<std::pair<std::uint32_t, real>> v{{0, r}};",
                      "std::array<int, 2> q{}; std::sort(q.begin(), q.end());",
                      "const vec3 n = glm::normalize(glm::cross(vec3(1, 0, 0), vec3(0, 1, 0)));",
                      "double x = M_PI * std::rand() / RAND_MAX + std::numeric_limits<real>::infinity();",
                      "return v.size() + rt::pi_real + detail::short_number(x).size() + n.x;")

    def test_a_name_declared_by_the_region_counts_only_in_its_scope(self):
        self.accepted("int fopen = 0;", "return fopen;")
        self.refused(["{ int fopen = 0; }", "fopen(\"x\", \"r\");"], "11:1", "found fopen")
        self.refused(["for (auto fopen : {1}) {}", "fopen(\"x\", \"r\");"], "11:1", "found fopen")
        self.refused(["auto l = [](int fopen) { return fopen; };", "return fopen(\"a\", \"b\");"], "11:8",
                     "found fopen")
        self.refused(["if (int fopen = 1) {} else { return fopen; }", "return fopen(\"a\", \"b\") != nullptr;"],
                     "11:8", "found fopen")
        self.refused(["[fopen = 1] { return fopen; }();", "fopen(\"a\", \"b\");"], "11:1", "found fopen")
        self.refused(["system(\"x\"); int system = 0;"], "10:1", "found system")
        # the body of an if, an else or a loop without braces is a scope of its own
        self.refused(["if (a) int fopen = 0;", "fopen(\"x\", \"r\");"], "11:1", "found fopen")
        self.refused(["if (a) {} else int b2 = 1, fopen = 0;", "fopen(\"x\", \"r\");"], "11:1", "found fopen")
        self.refused(["while (a) auto [fopen] = std::array<int, 1>{};", "fopen(\"x\", \"r\");"], "11:1",
                     "found fopen")

    def test_declarations_the_region_makes(self):
        self.accepted("for (int i = 0, j = 1; i < j; ++i) {}", "const auto [x, y] = std::pair<int, int>{1, 2};",
                      "auto g = [k = 3](int m, const auto& w) { return k + m + w; };",
                      "real t = 0, *u = &t, w[2] = {0, 1};",
                      "enum class mode { one, two };", "mode m = mode::one;",
                      "struct P { int q; int twice() const { return q * 2; } };", "P p{3};",
                      "using V = std::vector<real>;", "V vs(3);",
                      "std::vector<std::vector<int>> grid, other{{1}};",
                      "return x + y + g(1, 2) + *u + w[1] + (m == mode::two) + p.twice() + vs.size() + grid.size() "
                      "+ other.size();")

    def test_what_only_looks_like_a_declaration_declares_nothing(self):
        self.refused(["bool ok = true;", "ok && system, system(\"id\");"], "11:7", "found system")
        self.refused(["int vec3 = 0;", "vec3 && system, system(\"id\");"], "11:9", "found system")
        self.refused(["bool ok = true;", "int q = ok ? 1, system(\"id\") : 2;"], "11:17", "found system")
        self.refused(["int system(const char*);", "system(\"id\");"], "10:5", "a declaration of a function system")
        self.refused(["struct stat st;"], "10:1", "found struct stat")
        self.accepted("auto [system] = std::array<int, 1>{1};", "return system;")     # a binding shadows

    def test_keywords_that_reach_outside_the_function(self):
        cases = {"asm(\".incbin \\\"/etc/passwd\\\"\");":
                 "expected no inline assembly in an exercise region, found asm",
                 "_Pragma(\"once\") return 0;": "expected no pragma in an exercise region, found _Pragma",
                 "int (*p)() __attribute__((section(\".init_array\"))) = nullptr;":
                     "expected no compiler attribute in an exercise region, found __attribute__",
                 "extern char** environ;": "found extern",
                 "static int calls = 0;": "found static",
                 "thread_local int calls = 0;": "found thread_local",
                 "goto out;": "found goto",
                 "union U { long a; double b; };": "found union",
                 "template <class T> struct X {};": "found template",
                 "typedef int T;": "found typedef",
                 "struct S { friend int system(const char*); };": "found friend"}
        for line, fragment in cases.items():
            with self.subTest(line=line):
                self.assertIn(fragment, check(line))
                self.assertRegex(check(line), ONE_LINE)


class Attributes(Case):
    def test_standard_attributes_are_accepted(self):
        self.accepted("[[maybe_unused]] int v[2] = <% 1, 2 %>;",
                      "switch (v<:0:>) { case 1: [[fallthrough]]; default: break; }",
                      "[[maybe_unused, deprecated(\"why\")]] int w = 0;", "return v[0];")

    def test_a_vendors_attribute_is_refused_however_spelled(self):
        self.refused(["    [[gnu::section(\".init_array\")]] int x = 0;"], "10:5", "found [[gnu::section")
        self.refused(["    <:<:gnu::section(\".init_array\"):>:> int x = 0;"], "10:5", "found [[gnu::section")
        self.refused(["    [[ /* after [[ */ gnu::used ]] int x = 0;"], "10:5", "found [[gnu::used")
        self.refused(["    [ [ // a comment", "      gnu::constructor ] ] int x = 0;"], "10:5",
                     "found [[gnu::constructor")
        self.refused(["    [[using gnu: section(\".init_array\")]] int x = 0;"], "10:7", "found [[using")
        self.refused(["    [[maybe_unused, gnu::used]] int x = 0;"], "10:5", "found [[gnu::used")
        self.refused(["    [[constructor]] int x = 0;"], "10:7", "found [[constructor]]")


class Casts(Case):
    def test_casts_to_pointers_or_references(self):
        self.refused(["return (char*)p;"], "10:8", "found a cast to (char *)")
        self.refused(["return static_cast<void*>(p);"], "10:8", "found static_cast<void *>")
        self.refused(["return static_cast<const long&>(a);"], "10:8", "found static_cast<const long &>")
        self.refused(["return (std::uintptr_t)p;"], "10:9", "found std::uintptr_t")
        self.refused(["return reinterpret_cast<long>(p);"], "10:8", "no reinterpret_cast")
        self.refused(["return const_cast<int*>(p);"], "10:8", "no const_cast")
        self.refused(["using P = int*;"], "10:14", "an alias of a value type")
        self.refused(["return decltype(p)(0x401000);"], "10:8", "found decltype(...)(...)")

    def test_casts_from_what_is_visibly_a_pointer(self):
        self.refused(["return (long)&a;"], "10:8", "found (long) of a pointer")
        self.refused(["int x = 1; int* q = &x; return (long)q;"], "10:32", "of a pointer")
        self.refused(["auto s = \"abc\"; return std::size_t(s);"], "10:29", "size_t(...) of a pointer")
        self.refused(["real t[3]; return (long)t;"], "10:19", "of a pointer")
        self.refused(["return (long)+[] { return 1; };"], "10:8", "of a pointer")
        self.refused(["std::vector<int> v; return (long)v.data();"], "10:28", "of a pointer")

    def test_casts_of_values(self):
        self.accepted("(void)a;", "return (int)a + int(b) + static_cast<float>(a) + std::uint32_t(a) + real(2);")


class PpmWriter(Case):
    """Stage 02's PPM writer gets the stream members and the one cast it needs; no other region."""
    PPM = "include/rt/output/image_io.hpp"

    def test_the_writer_gets_write_put_and_its_cast(self):
        self.accepted("out << \"P6\\n\" << img.width << ' ' << img.height << \"\\n255\\n\" << std::endl;",
                      "const std::vector<std::uint8_t> bytes = to_rgb8(img, gamma);",
                      "out.put('\\n');",
                      "out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));",
                      rel=self.PPM)

    def test_nothing_that_opens_a_file_or_another_stream(self):
        self.refused(["out.rdbuf();"], "10:5", "found .rdbuf", rel=self.PPM)
        self.refused(["std::ofstream f(\"x\");"], "10:1", "found std::ofstream", rel=self.PPM)
        self.refused(["reinterpret_cast<long>(out);"], "10:1", "reinterpret_cast<const char*> only", rel=self.PPM)

    def test_other_regions_get_none_of_it(self):
        self.refused(["out.write(nullptr, 0);"], "10:5", "found .write")
        self.refused(["return reinterpret_cast<const char*>(&a)[0];"], "10:8", "no reinterpret_cast")
        self.refused(["return std::streamsize(1);"], "10:8", "found std::streamsize")


class Acceptance(unittest.TestCase):
    """Every body the project itself writes between markers is accepted."""

    def test_every_reference_body_and_every_kit_stub(self):
        regions = make_kit.scan_repository(REPO)
        self.assertGreater(len(regions), 30)
        for r in regions:
            lines = (REPO / r.path).read_text(encoding="utf-8").split("\n")
            with self.subTest(region=r.where()):
                self.assertEqual(splice.check_body(r.path, r.begin_line + 1, lines[r.begin_line:r.end_line - 1]), "")
                stub = make_kit.stripped_body(r, make_kit.stage_doc(REPO, r.stage))
                self.assertEqual(splice.check_body(r.path, r.begin_line + 1, stub), "")

    def test_every_planted_honest_mistake(self):
        for mistake in planted_mistakes.MISTAKES:
            _, planted, problems = planted_mistakes.planted_texts(REPO, mistake)
            self.assertEqual(problems, [])
            for rel, text in planted.items():
                for key, region in splice.read_student_file(rel, text).regions.items():
                    with self.subTest(mistake=mistake.label(), region=key):
                        self.assertEqual(region.problem, "")


class EntryPoint(unittest.TestCase):
    def test_read_student_file_looks_check_body_up_when_it_runs(self):
        text = "inline int f()\n{\n    // RT_EXERCISE_BEGIN(stage01: f)\n    std::exit(0);\n" \
               "    // RT_EXERCISE_END\n}\n"
        self.assertIn("found std::exit", splice.read_student_file(FX, text).regions[(1, "f")].problem)
        saved = splice.check_body
        splice.check_body = lambda *args, **kwargs: ""
        try:
            self.assertEqual(splice.read_student_file(FX, text).regions[(1, "f")].problem, "")
        finally:
            splice.check_body = saved

    def test_a_marker_note_shows_no_raw_control_byte(self):
        text = "inline int f()\n{\n    // RT_EXERCISE_BEGIN(stage1: f\x1b\udcff)\n    return 1;\n" \
               "    // RT_EXERCISE_END\n}\n"
        notes = splice.read_student_file(FX, text).notes
        self.assertTrue(any("\\x1b\\xff" in n for n in notes), notes)
        self.assertFalse(any("\x1b" in n or "\udcff" in n for n in notes))


if __name__ == "__main__":
    unittest.main()
