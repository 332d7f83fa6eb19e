"""What an exercise region may name.

A region is the body of one of rt's functions; the tests call that function and compare its
result. The names it needs are the language's, rt's API (tests/public_names.txt), the
enclosing function's parameters, GLM's vector algebra and a vetted part of the standard
library (math, algorithms, containers, limits). Everything else is refused by name, and
these lists say which: a name reaches the program around the function (ends or starts a
process, signals one, prints, opens a file, reads the environment) only through a name the
lists leave out. The names that come from rt's own headers (types, parameters, members,
enumerators) are read from include/rt with the lexer, so the lists follow the library;
DENIED is then taken out of every list, whatever the headers declare, because a parameter
or member called `write` elsewhere in rt would otherwise let `write(1, ...)` through.

region_check.py applies the lists to a region's tokens.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, FrozenSet, List, Set, Tuple

from . import lexer

REPO = Path(__file__).resolve().parents[2]
PUBLIC_NAMES = REPO / "tests" / "public_names.txt"

# Stage 02's PPM writer writes to the stream it is given: it alone may use the members
# and the one cast that takes (write, put, reinterpret_cast<const char*>, std::streamsize).
PPM_WRITER_FILE = "include/rt/output/image_io.hpp"

# --------------------------------------------------------------------------
# The language
# --------------------------------------------------------------------------

KEYWORDS = frozenset("""
alignas alignof asm auto bool break case catch char char16_t char32_t class const constexpr const_cast
continue decltype default delete do double dynamic_cast else enum explicit export extern false float for
friend goto if inline int long mutable namespace new noexcept nullptr operator private protected public
register reinterpret_cast return short signed sizeof static static_assert static_cast struct switch
template this thread_local throw true try typedef typeid typename union unsigned using virtual void
volatile wchar_t while
""".split())
TYPE_KEYWORDS = frozenset("auto bool char char16_t char32_t double float int long short signed unsigned void "
                          "wchar_t".split())
CV = frozenset({"const", "volatile"})
# Identifiers with a meaning in one place only (C++11 [lex.name]): fine in a local class.
CONTEXTUAL = frozenset({"override", "final"})

# Keywords a region may not use, with why: (what is expected instead, the hint).
REFUSED_KEYWORDS: Dict[str, Tuple[str, str]] = {
    "asm": ("no inline assembly in an exercise region",
            "write the function in C++ only: inline assembly can read a file while compiling (.incbin) and run "
            "any instruction"),
    "goto": ("no goto in an exercise region",
             "use a loop, break or return: GNU's computed goto (goto *p, &&label) jumps to any address"),
    "extern": ("no extern declaration in an exercise region",
               "a block-scope extern names a function or object outside the function (extern char** environ); "
               "use rt's API"),
    "static": ("no static local in an exercise region",
               "use const or constexpr: a static local keeps its value between calls, and its destructor runs "
               "after the tests, while an exercise computes from its arguments"),
    "thread_local": ("no thread_local in an exercise region",
                     "use a plain local: a thread_local outlives the call"),
    "namespace": ("no namespace or namespace alias in an exercise region",
                  "qualify names with std::, glm:: or rt:: as they are"),
    "template": ("no template in an exercise region",
                 "a function body declares no template; use a lambda with auto parameters"),
    "export": ("no export in an exercise region", "a function body exports nothing; remove it"),
    "union": ("no union in an exercise region",
              "a union reads one type's bytes as another's (a pointer as a number); use a struct"),
    "typedef": ("no typedef in an exercise region", "write using name = type; instead"),
    "friend": ("no friend in an exercise region",
               "a local class's friend names a function outside the region; make it a member"),
    "const_cast": ("no const_cast in an exercise region",
                   "an exercise changes only what its parameters let it change; copy the value instead"),
}
STANDARD_ATTRIBUTES = frozenset({"noreturn", "carries_dependency", "deprecated", "fallthrough", "nodiscard",
                                 "maybe_unused", "likely", "unlikely", "no_unique_address"})
# Reserved names (two underscores, or an underscore and a capital) that have a message of
# their own; any other reserved name is refused as the compiler's.
RESERVED_MEANING = {"__asm": "inline assembly", "__asm__": "inline assembly", "_Pragma": "pragma",
                    "__pragma": "pragma", "__attribute__": "compiler attribute",
                    "__attribute": "compiler attribute", "__declspec": "compiler attribute"}
TEST_FRAMEWORK = frozenset({"doctest", "TEST_CASE", "SUBCASE", "TEST_SUITE", "CHECK", "CHECK_FALSE", "CHECK_EQ",
                            "REQUIRE", "REQUIRE_FALSE", "REQUIRE_EQ", "WARN", "MESSAGE", "FAIL", "FAIL_CHECK",
                            "INFO", "CAPTURE", "Approx"})

# --------------------------------------------------------------------------
# The standard library: a vetted part
# --------------------------------------------------------------------------

# No name here has an overload or namesake that leaves the process: std::remove (the
# algorithm) is left out because <cstdio>'s std::remove deletes a file; getline, time and
# the like too.
STD_FUNCTIONS = frozenset("""
abs fabs sqrt cbrt pow exp exp2 expm1 log log2 log10 log1p sin cos tan asin acos atan atan2 sinh cosh tanh
asinh acosh atanh floor ceil round trunc lround llround nearbyint rint lrint llrint fmod remainder remquo
fmin fmax fdim fma hypot copysign nextafter nexttoward frexp ldexp modf scalbn scalbln ilogb logb isnan isinf
isfinite isnormal signbit fpclassify isgreater isgreaterequal isless islessequal islessgreater isunordered
erf erfc tgamma lgamma nan
sqrtf fabsf powf expf logf sinf cosf tanf asinf acosf atanf atan2f floorf ceilf roundf truncf fminf fmaxf fmodf
hypotf copysignf
min max minmax clamp swap sort stable_sort partial_sort nth_element min_element max_element minmax_element
find find_if find_if_not count count_if all_of any_of none_of for_each copy copy_if copy_n copy_backward
fill fill_n transform reverse rotate unique lower_bound upper_bound equal_range binary_search equal mismatch
partition stable_partition is_sorted is_sorted_until is_partitioned merge includes adjacent_find search
replace replace_if generate generate_n remove_if iter_swap lexicographical_compare is_permutation
next_permutation prev_permutation shuffle
accumulate iota inner_product partial_sum adjacent_difference reduce transform_reduce gcd lcm
move forward exchange make_pair make_tuple tie get as_const
begin end cbegin cend rbegin rend size empty data next prev distance advance back_inserter
make_optional to_string stoi stol stoll stoul stoull stof stod stold
visit holds_alternative get_if rand srand
""".split())
STD_TYPES = frozenset("""
size_t ptrdiff_t int8_t int16_t int32_t int64_t uint8_t uint16_t uint32_t uint64_t int_fast32_t
uint_fast32_t int_least32_t uint_least32_t
array vector pair tuple optional nullopt_t string string_view variant monostate function initializer_list
numeric_limits plus minus multiplies divides less greater less_equal greater_equal equal_to
exception runtime_error logic_error invalid_argument out_of_range domain_error range_error overflow_error
""".split())
# The types a pointer converts to as a number: its address (a class type's constructor
# taking a pointer is no such conversion).
ARITHMETIC_TYPES = frozenset("""
bool char char16_t char32_t wchar_t short int long signed unsigned float double size_t ptrdiff_t int8_t
int16_t int32_t int64_t uint8_t uint16_t uint32_t uint64_t int_fast32_t uint_fast32_t int_least32_t
uint_least32_t real
""".split())
STD_TYPE_TEMPLATES = frozenset("array vector pair tuple optional variant function initializer_list numeric_limits "
                               "plus minus multiplies divides less greater less_equal greater_equal "
                               "equal_to".split())
STD_VALUES = frozenset({"nullopt", "npos"})
STD_NAMES = STD_FUNCTIONS | STD_TYPES | STD_VALUES
# What the PPM writer needs beyond that (std::endl only flushes the stream it is given).
PPM_STD_NAMES = frozenset({"streamsize", "endl"})
PPM_MEMBERS = frozenset({"write", "put"})
# Object-like macros of the C library that are constants.
MACROS = frozenset("""
RAND_MAX INFINITY NAN HUGE_VAL HUGE_VALF M_PI M_PI_2 M_PI_4 M_1_PI M_2_PI M_2_SQRTPI M_E M_SQRT2 M_SQRT1_2
M_LN2 M_LN10 M_LOG2E M_LOG10E FLT_MAX FLT_MIN FLT_EPSILON FLT_TRUE_MIN DBL_MAX DBL_MIN DBL_EPSILON
DBL_TRUE_MIN INT_MAX INT_MIN UINT_MAX LONG_MAX LONG_MIN SIZE_MAX UINT8_MAX UINT16_MAX UINT32_MAX UINT64_MAX
INT8_MAX INT16_MAX INT32_MAX INT64_MAX INT32_MIN INT64_MIN CHAR_BIT FP_NAN FP_INFINITE FP_ZERO FP_NORMAL
FP_SUBNORMAL NULL
""".split())
# Members of the vetted containers, strings, optionals, pairs and numeric_limits, and the
# nested names after `>::`.
STD_MEMBERS = frozenset("""
size empty data begin end cbegin cend rbegin rend front back push_back emplace_back pop_back resize reserve
clear insert emplace erase at capacity shrink_to_fit assign swap fill first second has_value value value_or
reset length substr find rfind find_first_of find_last_of find_first_not_of find_last_not_of compare append
c_str npos max_size index valueless_by_exception
infinity max min lowest epsilon quiet_NaN signaling_NaN denorm_min round_error digits digits10 max_digits10
is_iec559 has_infinity has_quiet_NaN is_integer is_signed is_exact radix min_exponent max_exponent
min_exponent10 max_exponent10
value_type size_type difference_type iterator const_iterator reference const_reference
""".split())

# --------------------------------------------------------------------------
# GLM: its vector algebra (not glm::detail)
# --------------------------------------------------------------------------

GLM_FUNCTIONS = frozenset("""
abs sign floor trunc round roundEven ceil fract mod modf min max clamp mix step smoothstep isnan isinf fma
frexp ldexp pow exp log exp2 log2 sqrt inversesqrt radians degrees sin cos tan asin acos atan sinh cosh tanh
asinh acosh atanh length distance dot cross normalize faceforward reflect refract lessThan lessThanEqual
greaterThan greaterThanEqual equal notEqual any all not_ matrixCompMult outerProduct transpose determinant
inverse
""".split())
GLM_TYPES = frozenset("""
vec vec1 vec2 vec3 vec4 dvec1 dvec2 dvec3 dvec4 ivec2 ivec3 ivec4 uvec2 uvec3 uvec4 bvec2 bvec3 bvec4
mat mat2 mat3 mat4 mat2x2 mat2x3 mat2x4 mat3x2 mat3x3 mat3x4 mat4x2 mat4x3 mat4x4 dmat2 dmat3 dmat4
length_t qualifier
""".split())
GLM_TYPE_TEMPLATES = frozenset({"vec", "mat"})
GLM_VALUES = frozenset({"defaultp", "highp", "mediump", "lowp", "packed_highp", "packed_mediump", "packed_lowp"})
GLM_NAMES = GLM_FUNCTIONS | GLM_TYPES | GLM_VALUES
GLM_MEMBERS = frozenset("x y z w r g b a s t p q length".split())

# --------------------------------------------------------------------------
# What no list may hold
# --------------------------------------------------------------------------

DENIED_GROUPS: Dict[str, FrozenSet[str]] = {
    "process": frozenset("""
        system exit _exit _Exit quick_exit atexit at_quick_exit abort terminate fork vfork clone execl execle execlp
        execv execve execvp execvpe fexecve posix_spawn posix_spawnp popen pclose kill killpg raise signal
        sigaction sigprocmask pthread_sigmask pthread_kill pthread_create thread jthread async syscall ptrace
        wait waitpid waitid setsid setpgid setuid setgid seteuid setegid main longjmp setjmp siglongjmp
        sigsetjmp sleep usleep nanosleep alarm pause dlopen dlsym mmap munmap mprotect madvise brk sbrk prctl
        this_thread sigismember sigaddset sigemptyset sigwait sigpending set_terminate""".split()),
    "io": frozenset("""
        printf fprintf sprintf snprintf vprintf vfprintf dprintf puts fputs putchar fputc putc fwrite fread
        fgets fgetc getc getchar gets scanf fscanf sscanf perror fopen freopen fdopen fclose fflush fseek ftell
        rewind fileno tmpfile tmpnam mkstemp open openat creat close read write pread pwrite readv writev
        lseek dup dup2 pipe socket connect bind listen accept send recv sendto recvfrom ioctl fcntl fsync sync
        stat fstat lstat access opendir readdir unlink remove rename mkdir rmdir link symlink chmod chown
        truncate ftruncate chdir chroot cout cerr clog cin wcout wcerr wclog wcin ofstream ifstream fstream
        filebuf FILE stdout stderr stdin filesystem getline ostream istream iostream ostringstream
        istringstream stringstream streambuf basic_ostream basic_istream basic_ofstream basic_ifstream
        basic_fstream rdbuf""".split()),
    "environment": frozenset("""
        getenv secure_getenv setenv putenv unsetenv clearenv environ getpid getppid getuid geteuid getrlimit
        setrlimit sysconf pathconf uname gethostname time clock clock_gettime gettimeofday chrono errno
        locale setlocale""".split()),
}
DENIED: FrozenSet[str] = frozenset().union(*DENIED_GROUPS.values())
# Members that reach a stream's buffer or a file, or a thread's handle.
DENIED_MEMBERS = frozenset("""
write put flush rdbuf open close tie imbue exceptions seekp seekg tellp tellg read get getline ignore peek
putback unget readsome gcount sputn sputc pubsetbuf pubsync native_handle detach sync_with_stdio
""".split())
# rt's API that touches the file system or the process: loading and saving files (a scene
# read from a string too: its mesh statements read OBJ files), checking paths, the
# interrupt handlers, the memory limit of the machine.
RT_REFUSED = frozenset("""
check_readable check_writable check_image_output check_image_path check_not_input files_read load_input
load_obj load_scene save_image save_image_encoded image_file image_file_encoded output_file write_atomically
write_all_atomically set_interrupt_cleanup memory_limit check_memory_for load_scene_from_string
""".split())


def denied_group(name: str) -> str:
    """"process", "io" or "environment" when `name` is denied, else ""."""
    for group, members in DENIED_GROUPS.items():
        if name in members:
            return group
    return ""


# --------------------------------------------------------------------------
# rt's names, read from its headers
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class RtNames:
    api: FrozenSet[str]                      # tests/public_names.txt, less RT_REFUSED
    parameters: FrozenSet[str]               # every function parameter the headers name
    members: FrozenSet[str]                  # every name the headers declare or use after . or ->
    types: FrozenSet[str]                    # structs, classes, enums, aliases, template parameters
    type_templates: FrozenSet[str]           # class and alias templates
    pointer_aliases: FrozenSet[str]          # aliases of pointer or reference types
    qualified: Dict[str, FrozenSet[str]]     # Q -> the names the headers write after Q::
    detail: FrozenSet[str]                   # what the reference's regions use after detail::
    exercise_parameters: Dict[str, FrozenSet[str]]   # header -> its exercise functions' parameters


def _is_type_keyword(t: lexer.Token) -> bool:
    return t.kind == "name" and (t.text in TYPE_KEYWORDS or t.text in CV)


def _scan_header(toks: List[lexer.Token], out: Dict[str, Set[str]], qualified: Dict[str, Set[str]]) -> None:
    """Adds the names one header declares and uses to `out` (by kind) and `qualified`."""
    stack: List[int] = []
    n = len(toks)
    for k, t in enumerate(toks):
        if t.kind == "punct":
            if t.text in lexer.OPENING:
                stack.append(k)
            elif t.text in lexer.CLOSING and stack:
                stack.pop()
            continue
        if t.kind != "name":
            continue
        prev = toks[k - 1] if k else None
        nxt = toks[k + 1] if k + 1 < n else None
        if prev is not None and prev.text in (".", "->"):
            out["members"].add(t.text)
            continue
        if prev is not None and prev.text == "::":
            q = toks[k - 2] if k >= 2 and toks[k - 2].kind == "name" else None
            if q is not None:
                qualified.setdefault(q.text, set()).add(t.text)
            continue
        if t.text in KEYWORDS or nxt is None or prev is None:
            continue
        if prev.text in ("struct", "class", "enum", "union") and nxt.text in ("{", ":", ";", "final"):
            out["types"].add(t.text)
            if _template_head_before(toks, k):
                out["templates"].add(t.text)
            continue
        if prev.text == "using" and nxt.text == "=":
            out["types"].add(t.text)
            if _aliases_a_pointer(toks, k + 2):
                out["pointer_aliases"].add(t.text)
            if _template_head_before(toks, k):
                out["templates"].add(t.text)
            continue
        if prev.text in ("class", "typename") and k >= 2 and toks[k - 2].text in ("<", ",") \
                and nxt.text in (",", ">", "=", "..."):
            out["types"].add(t.text)                       # a template's type parameter
            continue
        declarator = (prev.kind == "name" and (prev.text not in KEYWORDS or _is_type_keyword(prev))) \
            or prev.text in (">", ">>", "*", "&", "&&")
        if declarator and nxt.text in ("(", ";", "=", ",", "{", ")", "[", ":"):
            out["members"].add(t.text)
            if stack and toks[stack[-1]].text == "(" and nxt.text in (",", ")", "="):
                out["parameters"].add(t.text)
        if prev.text in ("{", ",") and stack and _enum_body(toks, stack[-1]):
            out["members"].add(t.text)


def _aliases_a_pointer(toks: List[lexer.Token], start: int) -> bool:
    """Whether the type from `start` to the `;` is a pointer or a reference (a `*` or `&`
    outside template arguments, or a function pointer's `(*`); std::function<void(int&)>
    is neither."""
    angles = 0
    for j in range(start, len(toks)):
        text = toks[j].text
        if text == ";":
            return False
        angles += {"<": 1, ">": -1, ">>": -2}.get(text, 0)
        if angles <= 0 and (text in ("*", "&", "&&") or (text == "(" and toks[j + 1].text == "*")):
            return True
    return False


def _template_head_before(toks: List[lexer.Token], k: int) -> bool:
    """Whether the declaration of the name at `k` starts with template <...>."""
    j = k - 1
    while j >= 0 and toks[j].text not in (";", "{", "}"):
        if toks[j].text == "template":
            return True
        j -= 1
    return False


def _enum_body(toks: List[lexer.Token], brace: int) -> bool:
    j = brace - 1
    while j >= 0 and toks[j].text not in (";", "{", "}", ")"):
        if toks[j].text == "enum":
            return True
        j -= 1
    return False


def _region_bodies() -> List[Tuple[str, List[str], List[str]]]:
    """(header, the function's parameter names, the body's lines) of every region of the
    reference."""
    import sys
    sys.path.insert(0, str(REPO / "tools"))
    import make_kit  # noqa: E402  (tools/make_kit.py: the region parser)
    out = []
    for r in make_kit.scan_repository(REPO):
        lines = (REPO / r.path).read_text(encoding="utf-8").split("\n")
        out.append((r.path, [name for name, _ in r.parameters], lines[r.begin_line:r.end_line - 1]))
    return out


def _sources() -> List[Path]:
    """What rt_names reads or is made by."""
    here = Path(__file__).resolve().parent
    return ([here / "names.py", here / "lexer.py", REPO / "tools" / "make_kit.py", PUBLIC_NAMES]
            + sorted((REPO / "include" / "rt").rglob("*.hpp")))


def _to_json(rt: RtNames) -> Dict[str, object]:
    out: Dict[str, object] = {}
    for field, value in vars(rt).items():
        if isinstance(value, dict):
            out[field] = {k: sorted(v) for k, v in value.items()}
        else:
            out[field] = sorted(value)
    return out


def _from_json(data: Dict[str, object]) -> RtNames:
    fields = {}
    for field, value in data.items():
        if isinstance(value, dict):
            fields[field] = {k: frozenset(v) for k, v in value.items()}
        else:
            fields[field] = frozenset(value)  # type: ignore[arg-type]
    return RtNames(**fields)  # type: ignore[arg-type]


_KEPT: Dict[str, RtNames] = {}


def keep_in(folder: Path) -> None:
    """Reads rt's names from `folder` when it holds them for these very sources, else reads
    them from the headers and leaves them there. Reading the headers takes about a second;
    a grader that grades many submissions does it once. `folder` must be the grader's own
    (a cache only it can write): whoever writes it sets what a region may name."""
    h = hashlib.sha256()
    for source in _sources():
        h.update(str(source).encode() + b"\0" + source.read_bytes() + b"\0")
    kept = folder / f"names-{h.hexdigest()[:24]}.json"
    try:
        _KEPT["rt"] = _from_json(json.loads(kept.read_text(encoding="utf-8")))
        return
    except (OSError, ValueError, TypeError):
        pass
    rt = rt_names()
    folder.mkdir(mode=0o700, parents=True, exist_ok=True)
    for old in folder.glob("names-*.json"):
        old.unlink()
    staging = kept.with_suffix(f".tmp{os.getpid()}")
    staging.write_text(json.dumps(_to_json(rt)), encoding="utf-8")
    os.chmod(staging, 0o600)
    os.replace(staging, kept)
    _KEPT["rt"] = rt


def rt_names() -> RtNames:
    """rt's names, read once from this repository's include/rt and tests/public_names.txt
    (or kept by keep_in)."""
    if "rt" not in _KEPT:
        _KEPT["rt"] = _read_rt_names()
    return _KEPT["rt"]


def _read_rt_names() -> RtNames:
    api = {line.strip() for line in PUBLIC_NAMES.read_text(encoding="utf-8").splitlines()
           if line.strip() and not line.startswith("#")}
    found: Dict[str, Set[str]] = {k: set() for k in ("members", "types", "templates", "pointer_aliases",
                                                     "parameters")}
    qualified: Dict[str, Set[str]] = {}
    for header in sorted((REPO / "include" / "rt").rglob("*.hpp")):
        _scan_header(lexer.header_tokens(header.read_text(encoding="utf-8")), found, qualified)
    detail: Set[str] = set()
    exercise: Dict[str, Set[str]] = {}
    for rel, parameters, body in _region_bodies():
        exercise.setdefault(rel, set()).update(parameters)
        toks = lexer.tokens("\n".join(body))
        for k in range(2, len(toks)):
            if toks[k - 1].text == "::" and toks[k - 2].text == "detail":
                detail.add(toks[k].text)
    found["types"] -= found["pointer_aliases"]
    return RtNames(
        api=frozenset(api - RT_REFUSED - DENIED),
        parameters=frozenset(found["parameters"] - DENIED),
        members=frozenset((found["members"] | found["parameters"]) - DENIED - DENIED_MEMBERS - RT_REFUSED),
        types=frozenset(found["types"] - DENIED),
        type_templates=frozenset(found["templates"] - DENIED),
        pointer_aliases=frozenset(found["pointer_aliases"]),
        qualified={q: frozenset(v - DENIED - RT_REFUSED) for q, v in qualified.items()
                   if q not in ("std", "glm", "rt", "detail")},
        detail=frozenset(detail),
        exercise_parameters={rel: frozenset(v) for rel, v in exercise.items()},
    )


@functools.lru_cache(maxsize=None)
def unqualified(ppm: bool) -> FrozenSet[str]:
    """The names a region may use without a qualifier (besides its own declarations)."""
    rt = rt_names()
    names = rt.api | rt.parameters | rt.types | STD_NAMES | GLM_NAMES | MACROS | {"rt", "glm", "std", "detail"}
    if ppm:
        names |= PPM_STD_NAMES
    return frozenset(names - DENIED - RT_REFUSED - rt.pointer_aliases)


@functools.lru_cache(maxsize=None)
def members(ppm: bool) -> FrozenSet[str]:
    """The names a region may use after . or -> (besides the members of its own types)."""
    rt = rt_names()
    names = rt.members | STD_MEMBERS | GLM_MEMBERS
    return frozenset(names | PPM_MEMBERS) if ppm else frozenset(names - PPM_MEMBERS)


@functools.lru_cache(maxsize=None)
def after_qualifier(qualifier: str, ppm: bool) -> FrozenSet[str]:
    """The names a region may write after `qualifier::` (std, glm, rt, detail or one of rt's
    scopes, such as projection::)."""
    rt = rt_names()
    if qualifier == "std":
        return STD_NAMES | PPM_STD_NAMES if ppm else STD_NAMES
    if qualifier == "glm":
        return GLM_NAMES
    if qualifier == "rt":
        return frozenset((rt.api | {"detail"}) - rt.pointer_aliases)
    if qualifier == "detail":
        return rt.detail
    return rt.qualified.get(qualifier, frozenset())


@functools.lru_cache(maxsize=None)
def type_names(qualifier: str) -> FrozenSet[str]:
    """The names that are types after `qualifier::` ("" for none)."""
    if qualifier == "std":
        return STD_TYPES | {"streamsize"}
    if qualifier == "glm":
        return GLM_TYPES
    return rt_names().types | (GLM_TYPES if qualifier == "" else frozenset())


@functools.lru_cache(maxsize=None)
def type_templates(qualifier: str) -> FrozenSet[str]:
    if qualifier == "std":
        return STD_TYPE_TEMPLATES
    if qualifier == "glm":
        return GLM_TYPE_TEMPLATES
    return rt_names().type_templates | (GLM_TYPE_TEMPLATES if qualifier == "" else frozenset())
