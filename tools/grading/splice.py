"""Only the exercise regions come from a submission.

For each header of the reference that holds exercise regions, the grader reads the
student's copy of it, takes the lines between each pair of markers

    // RT_EXERCISE_BEGIN(stageNN: title)
    ...the student's lines...
    // RT_EXERCISE_END

and matches them to the reference's region by file, stage and title. Every other line of
the submission is ignored. A region's lines must stay inside the function body: no
preprocessor directive (which would change code outside it, or read a file), no brace
that closes the function, no string or comment left open (which would swallow the code
after the region), no `asm` (which can read a file while compiling). Such a region is
refused, and its stage scores zero with a message naming the line.

The grader then composes the headers each stage's tests compile against (an *overlay*):
the reference's text with, region by region, the reference's body, the kit's not-done
body, or the student's lines, and remembers which line of the overlay came from which
line of the student's file, so that a compiler message names the student's own line.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterable, List, Optional, Sequence, Set, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
import make_kit  # noqa: E402  (tools/make_kit.py: the markers and the kit's bodies)

# Identifiers a region may not use: inline assembly reads files at compile time
# (.incbin) and defines symbols; _Pragma is a directive in operator form; a compiler
# attribute can place a function in the program's start-up list (section .init_array)
# and run it before the tests begin.
FORBIDDEN_WORDS = {"asm": "inline assembly", "__asm": "inline assembly", "__asm__": "inline assembly",
                   "_Pragma": "a pragma", "__pragma": "a pragma",
                   "__attribute__": "compiler attribute", "__attribute": "compiler attribute",
                   "__declspec": "compiler attribute"}
# [[gnu::section(...)]], [[using gnu: ...]]: the same attributes in the standard's spelling
# (the unqualified ones, [[maybe_unused]] and the like, are accepted)
SCOPED_ATTRIBUTE_RE = re.compile(r"(\[|<:)\s*(\[|<:)\s*(using\b|[A-Za-z_]\w*\s*::)")
# Digraphs: the alternative spellings of brackets and of '#'.
DIGRAPHS = {"<%": "{", "%>": "}", "<:": "[", ":>": "]"}
STRING_PREFIXES = ("u8R", "uR", "UR", "LR", "R", "u8", "u", "U", "L")


@dataclass
class StudentRegion:
    """One region of the student's file: its stage, title and lines (1-based numbers in
    the student's file)."""
    stage: int
    title: str
    begin_line: int               # the BEGIN marker's line
    end_line: int                 # the END marker's line
    body: List[str]               # the lines between the markers
    problem: str = ""             # why it is refused ("" when it is accepted)


@dataclass
class StudentFile:
    """What the grader takes from one of the student's headers."""
    rel: str                                   # include/rt/sphere.hpp
    regions: Dict[Tuple[int, str], StudentRegion] = field(default_factory=dict)
    notes: List[str] = field(default_factory=list)   # markers the grader could not use
    lines: List[str] = field(default_factory=list)


def _marker(line: str) -> Optional[Tuple[str, str]]:
    """('begin', inside) or ('end', '') when the line is a marker comment alone on its line."""
    stripped = line.strip()
    if not stripped.startswith("//"):
        return None
    body = stripped[2:].strip()
    begin = make_kit.BEGIN_RE.match(body)
    if begin:
        return "begin", begin.group("inside")
    if make_kit.END_RE.match(body):
        return "end", ""
    return None


def region_key(inside: str) -> Optional[Tuple[int, str]]:
    m = make_kit.BEGIN_INSIDE_RE.match(inside)
    return (int(m.group("stage")), m.group("title")) if m else None


def normalise(text: str) -> str:
    """The text with Windows line ends and a byte-order mark removed."""
    if text.startswith("\ufeff"):
        text = text[1:]
    return text.replace("\r\n", "\n").replace("\r", "\n")


def read_student_file(rel: str, text: str) -> StudentFile:
    """The regions of the student's copy of `rel`, each checked (check_body)."""
    out = StudentFile(rel)
    lines = normalise(text).split("\n")
    out.lines = lines
    open_at: Optional[Tuple[int, str, int]] = None   # (line, inside, column)
    seen: Dict[Tuple[int, str], int] = {}
    for number, line in enumerate(lines, start=1):
        marker = _marker(line)
        if marker is None:
            continue
        column = len(line) - len(line.lstrip()) + 1
        kind, inside = marker
        if kind == "begin":
            if open_at is not None:
                key = region_key(open_at[1])
                if key is not None:
                    out.regions.setdefault(key, StudentRegion(
                        key[0], key[1], open_at[0], number, [],
                        f"{rel}:{number}:{column}: expected RT_EXERCISE_END for the region opened at line "
                        f"{open_at[0]}, found another RT_EXERCISE_BEGIN; keep both marker lines of "
                        f"every region as the kit has them"))
            open_at = (number, inside, column)
            continue
        if open_at is None:
            out.notes.append(f"{rel}:{number}:{column}: expected RT_EXERCISE_END after an RT_EXERCISE_BEGIN, "
                             f"found no open region; this marker is ignored")
            continue
        begin_line, inside, begin_column = open_at
        open_at = None
        key = region_key(inside)
        if key is None:
            out.notes.append(f"{rel}:{begin_line}:{begin_column}: expected RT_EXERCISE_BEGIN(stageNN: title) "
                             f"as the kit has it, found \"{inside}\"; this region is ignored")
            continue
        body = lines[begin_line:number - 1]
        region = StudentRegion(key[0], key[1], begin_line, number, body)
        if key in seen:
            region.problem = (f"{rel}:{begin_line}:{begin_column}: expected one region stage{key[0]:02d}: "
                              f"{key[1]}, found a second one (the first at line {seen[key]}); keep one")
            out.regions[key] = region
            continue
        seen[key] = begin_line
        region.problem = check_body(rel, begin_line + 1, body)
        out.regions[key] = region
    if open_at is not None:
        key = region_key(open_at[1])
        if key is not None:
            out.regions[key] = StudentRegion(
                key[0], key[1], open_at[0], len(lines), [],
                f"{rel}:{open_at[0]}:{open_at[2]}: expected RT_EXERCISE_END for this region, found the end "
                f"of the file; keep both marker lines of every region as the kit has them")
    return out


# --------------------------------------------------------------------------
# Checking a region's lines
# --------------------------------------------------------------------------

def check_body(rel: str, first_line: int, body: Sequence[str]) -> str:
    """'' when the lines can stand for a function's body, else the first problem as one
    line `file:line:col: expected ..., found ...; hint`."""
    text = "\n".join(body)
    n = len(text)
    i = 0
    line, line_start = first_line, 0
    brackets: List[Tuple[str, int, int]] = []     # (opening bracket, line, column)
    pairs = {"}": "{", ")": "(", "]": "["}

    def where(at: int) -> str:
        return f"{rel}:{line}:{at - line_start + 1}"

    def fail(at: int, expected: str, found: str, hint: str) -> str:
        return f"{where(at)}: expected {expected}, found {found}; {hint}"

    directive_hint = ("the grader takes only the lines between your markers, so a directive there "
                      "would change code outside your function; use the header's own #include lines")
    while i < n:
        ch = text[i]
        if ch == "\n":
            line += 1
            i += 1
            line_start = i
            continue
        if ch in " \t\f\v":
            i += 1
            continue
        if ch == "\\":
            rest = text[i + 1:text.find("\n", i) if "\n" in text[i:] else n]
            if rest.strip() == "":
                return fail(i, "no backslash at the end of a line", "one",
                            "it joins the next line to this one (a line splice); remove it")
            i += 1
            continue
        if text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            if text[i:end].rstrip().endswith("\\"):
                return fail(i, "a comment that ends with its line", "a backslash at its end",
                            "it continues the comment onto the next line; remove the backslash")
            i = end
            continue
        if text.startswith("/*", i):
            close = text.find("*/", i + 2)
            if close < 0:
                return fail(i, "*/ closing this comment inside the region", "the end of the region",
                            "close the comment before RT_EXERCISE_END")
            line += text.count("\n", i, close)
            if "\n" in text[i:close]:
                line_start = text.rfind("\n", i, close) + 1
            i = close + 2
            continue
        if ch == "#" or text.startswith("%:", i) or text.startswith("??=", i):
            m = re.match(r"(#|%:|\?\?=)\s*(\w*)", text[i:])
            word = m.group(2) if m else ""
            found = f"#{word}" if word else "#"
            return fail(i, "no preprocessor directive in an exercise region", found, directive_hint)
        if ch.isalpha() or ch == "_" or ord(ch) > 127:
            j = i + 1
            while j < n and (text[j].isalnum() or text[j] == "_" or ord(text[j]) > 127):
                j += 1
            word = text[i:j]
            if j < n and text[j] in "\"'" and word in STRING_PREFIXES:
                if text[j] == '"' and word.endswith("R"):
                    open_paren = text.find("(", j + 1)
                    delimiter = text[j + 1:open_paren] if open_paren >= 0 else ""
                    if open_paren < 0 or len(delimiter) > 16 or re.search(r"[\s\\()]", delimiter):
                        return fail(i, "a raw string R\"delimiter(...)delimiter\"", "a malformed one",
                                    "check the opening of the raw string")
                    closing = ")" + delimiter + '"'
                    close = text.find(closing, open_paren + 1)
                    if close < 0:
                        return fail(i, "the raw string closed inside the region", "the end of the region",
                                    "close it before RT_EXERCISE_END")
                    end = close + len(closing)
                    line += text.count("\n", i, end)
                    if "\n" in text[i:end]:
                        line_start = text.rfind("\n", i, end) + 1
                    i = end
                    continue
                i = j   # the literal follows: the quote is read next
                continue
            if word in FORBIDDEN_WORDS:
                return fail(i, f"no {FORBIDDEN_WORDS[word]} in an exercise region", word,
                            "write the function in C++ only")
            if word == "doctest" or word.startswith("DOCTEST_"):
                return fail(i, "no use of the test framework in an exercise region", word,
                            "the library's code does not call doctest")
            i = j
            continue
        if ch in "\"'":
            j = i + 1
            while j < n and text[j] != ch and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            if j >= n or text[j] != ch:
                what = "string" if ch == '"' else "character literal"
                return fail(i, f"the {what} closed on its line", "the end of the line",
                            f"add the closing {ch}")
            i = j + 1
            continue
        if ch.isdigit() or (ch == "." and i + 1 < n and text[i + 1].isdigit()):
            j = i + 1
            while j < n:
                c = text[j]
                if c in "eEpP" and j + 1 < n and text[j + 1] in "+-":
                    j += 2
                elif c.isalnum() or c in "_.":
                    j += 1
                elif c == "'" and j + 1 < n and (text[j + 1].isalnum() or text[j + 1] == "_"):
                    j += 2   # a digit separator, 1'000
                else:
                    break
            i = j
            continue
        two = text[i:i + 2]
        if two in DIGRAPHS and not (two == "<:" and text.startswith("<::", i) and
                                    not text.startswith("<:::", i) and not text.startswith("<::>", i)):
            ch = DIGRAPHS[two]
            step = 2
        else:
            step = 1
        attribute = SCOPED_ATTRIBUTE_RE.match(text, i) if ch == "[" else None
        if attribute:
            return fail(i, "no attribute with a vendor's prefix in an exercise region",
                        re.sub(r"\s", "", attribute.group(0)),
                        "write the function in C++ only; [[maybe_unused]] and the like are fine")
        if ch in "{([":
            brackets.append((ch, line, i - line_start + 1))
        elif ch in "})]":
            if not brackets:
                return fail(i, "code that stays inside the function body", f"an unmatched '{ch}'",
                            "the region is the function's whole body: keep its braces balanced")
            opening = brackets.pop()
            if opening[0] != pairs[ch]:
                return fail(i, f"a bracket closing the '{opening[0]}' of line {opening[1]}", f"'{ch}'",
                            "check the brackets")
        i += step
    if brackets:
        opening, at_line, column = brackets[-1]
        closing = {"{": "}", "(": ")", "[": "]"}[opening]
        return (f"{rel}:{at_line}:{column}: expected '{closing}' for this '{opening}' before RT_EXERCISE_END, "
                f"found the end of the region; the region is the function's whole body: keep its brackets "
                f"balanced")
    return ""


# --------------------------------------------------------------------------
# Composing the headers a stage compiles against
# --------------------------------------------------------------------------

@dataclass
class Composed:
    text: str
    # overlay line -> the student's line: for a line of a student's region its own number,
    # for any other line the student's line that stands for it best (0 when none)
    lines: Dict[int, int]
    exact: Set[int] = field(default_factory=set)     # the overlay lines that are the student's


ERROR_INCLUDE_RE = re.compile(r'^\s*#\s*include\s*[<"]([\w./]*/)?(rt/)?error\.hpp[>"]', re.MULTILINE)


def compose(rel: str, reference_text: str, regions: Sequence[make_kit.Region],
            choice: Dict[int, object], doc_of: Dict[int, Optional[str]],
            student: Optional[StudentFile], declare: Iterable[int] = (),
            keep: Optional[Dict[int, str]] = None) -> Composed:
    """The reference's `rel` with each region's body chosen by `choice[index into regions]`:
    "reference", "stub" (the kit's not-done body) or a StudentRegion. Lines outside the
    regions are the reference's. The functions of the regions in `declare` become bare
    declarations (their definitions are compiled elsewhere: split_form); after the function
    of each region in `keep`, its line is added."""
    ref_lines = reference_text.split("\n")
    out: List[Tuple[str, int]] = []
    exact_lines: List[int] = []     # indexes into out
    order = sorted(range(len(regions)), key=lambda k: regions[k].begin_line)
    declare = set(declare)
    keep = keep or {}
    at = 0     # next reference line (0-based)
    stub_used = False
    segment = 0
    student_segments = _segments(student) if student is not None else []

    def copy(until: int) -> None:
        """The reference's lines from `at` up to `until` (exclusive)."""
        nonlocal at
        offset0 = at
        for idx in range(at, until):
            out.append((ref_lines[idx], _segment_line(student_segments, segment, idx - offset0)))
        at = max(at, until)

    for k in order:
        r = regions[k]
        mine = student.regions.get((r.stage, r.title)) if student is not None else None
        stand_in = mine.begin_line if mine is not None else 0
        span = function_span(ref_lines, r) if (k in declare or k in keep) else None
        if k in declare and span is not None:
            open_idx, open_col, close_idx, close_col = span
            copy(open_idx)
            head = ref_lines[open_idx][:open_col].rstrip()
            if head.strip():
                out.append((head + ";", stand_in))
            elif out and "//" not in out[-1][0] and "/*" not in out[-1][0]:
                out[-1] = (out[-1][0].rstrip() + ";", out[-1][1])   # the brace alone on its line
                out.append(("", stand_in))                            # keeps the line count
            else:
                out.append((";", stand_in))
            tail = ref_lines[close_idx][close_col + 1:]
            if tail.strip():
                out.append((tail, stand_in))
            at = close_idx + 1
            segment += 1
            continue
        copy(r.begin_line)    # up to the BEGIN marker, inclusive
        segment += 1
        chosen = choice.get(k, "reference")
        if isinstance(chosen, StudentRegion):
            for offset, body_line in enumerate(chosen.body):
                exact_lines.append(len(out))
                out.append((body_line, chosen.begin_line + 1 + offset))
        else:
            if chosen == "stub":
                body = make_kit.stripped_body(r, doc_of.get(r.stage))
                stub_used = True
            else:
                body = ref_lines[r.begin_line:r.end_line - 1]
            out.extend((b, stand_in) for b in body)
        at = r.end_line - 1     # the END marker comes next
        if k in keep and span is not None:
            copy(span[2] + 1)   # through the function's closing brace
            out.append((keep[k], stand_in))
    copy(len(ref_lines))
    text = "\n".join(l for l, _ in out)
    # the kit's bodies (ours, or the student's unchanged ones) throw rt::exercise_not_done
    if (stub_used or "exercise_not_done" in text) and not ERROR_INCLUDE_RE.search(text):
        with_include = make_kit._with_error_include(rel, text).split("\n")
        inserted = next((k for k, (a, b) in enumerate(zip(with_include, (l for l, _ in out))) if a != b),
                        len(out))
        out.insert(inserted, (with_include[inserted], 0))
        exact_lines = [k + 1 if k >= inserted else k for k in exact_lines]
        text = "\n".join(l for l, _ in out)
    return Composed(text, {k + 1: student_line for k, (_, student_line) in enumerate(out)},
                    {k + 1 for k in exact_lines})


def _code_part(line: str) -> str:
    """The line without a // comment (the reference's signatures hold no string with //)."""
    cut = line.find("//")
    return line if cut < 0 else line[:cut]


def function_span(lines: List[str], region: make_kit.Region) -> Optional[Tuple[int, int, int, int]]:
    """(line, column) of the '{' that opens the region's function and of the '}' that closes
    it, 0-based: the last brace before the BEGIN marker and the first after the END marker
    (make_kit --check guarantees the region is the whole body)."""
    open_at = close_at = None
    for idx in range(region.begin_line - 2, -1, -1):
        col = _code_part(lines[idx]).rfind("{")
        if col >= 0:
            open_at = (idx, col)
            break
    for idx in range(region.end_line, len(lines)):
        col = _code_part(lines[idx]).find("}")
        if col >= 0:
            close_at = (idx, col)
            break
    if open_at is None or close_at is None:
        return None
    return open_at + close_at


def split_form(lines: List[str], region: make_kit.Region, key: str) -> Optional[str]:
    """When the region's function can be compiled apart from the tests that call it (a
    non-template `inline` function at namespace level, with a return type written out),
    the line that, placed after it, makes a unit emit it: a pointer to it, of its exact
    type; None otherwise (templates, `auto`, members, `static`)."""
    span = function_span(lines, region)
    if span is None:
        return None
    open_idx, open_col = span[0], span[1]
    parts = [_code_part(lines[open_idx])[:open_col]]
    idx = open_idx - 1
    while idx >= 0:
        code = _code_part(lines[idx]).rstrip()
        if not code.strip() or code.rstrip().endswith((";", "}", "{")) or lines[idx].lstrip().startswith("#"):
            break
        parts.insert(0, code)
        idx -= 1
    first = idx + 1
    if first > open_idx or lines[first][:1].isspace():
        return None        # indented: a member function, or not a plain declaration
    signature = " ".join(p.strip() for p in parts).strip()
    signature = re.sub(r"\[\[.*?\]\]", " ", signature).strip()
    if not re.match(r"inline\b", signature) or re.search(r"\b(template|static|auto|decltype|constexpr|"
                                                          r"consteval|operator|friend|virtual)\b", signature):
        return None
    group = make_kit._parameter_group(signature)
    if group is None:
        return None
    head = signature[:group[0]].rstrip()
    m = re.search(r"([A-Za-z_]\w*)$", head)
    if not m or m.group(1) != region.function:
        return None
    return_type = re.sub(r"^inline\s+", "", head[:m.start()]).strip()
    if not return_type or "::" in head[m.start() - 2:m.start()]:
        return None
    inside = signature[group[0] + 1:group[1] - 1]
    parameters = []
    for part in make_kit._split_top_level(inside, ","):
        part = re.split(r"(?<![=!<>])=(?!=)", part, maxsplit=1)[0].strip()   # no default argument
        if part:
            parameters.append(part)
    tail = signature[group[1]:].strip()
    if tail:
        return None        # noexcept, a trailing return type, requires ...
    return (f"[[gnu::used]] static {return_type} (*const rt_grader_keep_{key})({', '.join(parameters)}) = "
            f"&{region.function}; // tools/grade.py: this unit emits {region.function}")


def _segments(student: StudentFile) -> List[Tuple[int, int]]:
    """(first line, number of lines) of each stretch of the student's file outside the
    regions: before the first BEGIN (inclusive), between an END and the next BEGIN, after
    the last END. Regions that are refused still mark their stretch."""
    regions = sorted(student.regions.values(), key=lambda r: r.begin_line)
    segments, at = [], 1
    for r in regions:
        segments.append((at, r.begin_line - at + 1))
        at = r.end_line
    segments.append((at, len(student.lines) - at + 1))
    return segments


def _segment_line(segments: List[Tuple[int, int]], segment: int, offset: int) -> int:
    if segment < len(segments):
        first, count = segments[segment]
        if offset < count:
            return first + offset
    return 0


def outside_differences(student: StudentFile, reference_text: str,
                        regions: Sequence[make_kit.Region]) -> Optional[int]:
    """The first line of the student's file outside the regions that differs from the
    reference's (blank lines, indentation and the kit's error.hpp line aside); None when
    they agree."""
    def outside(lines: List[str], spans: Iterable[Tuple[int, int]]) -> List[Tuple[int, str]]:
        inside = set()
        for begin, end in spans:
            inside.update(range(begin + 1, end))       # the body lines, 1-based
        kept = []
        for number, l in enumerate(lines, start=1):
            bare = " ".join(l.split())
            if number in inside or not bare or ERROR_INCLUDE_RE.match(bare):
                continue
            kept.append((number, bare))
        return kept

    mine = outside(student.lines, [(r.begin_line, r.end_line) for r in student.regions.values()])
    theirs = outside(normalise(reference_text).split("\n"), [(r.begin_line, r.end_line) for r in regions])
    for (number, a), (_, b) in zip(mine, theirs):
        if a != b:
            return number
    if len(mine) != len(theirs):
        return mine[len(theirs)][0] if len(mine) > len(theirs) else (mine[-1][0] if mine else 1)
    return None


# --------------------------------------------------------------------------
# Compiler messages in the student's own line numbers
# --------------------------------------------------------------------------

@dataclass
class LineMaps:
    """Where each overlay lives and which student line each of its lines stands for."""
    roots: Dict[str, Dict[str, Composed]] = field(default_factory=dict)  # overlay root -> rel -> its lines
    student_lines: Dict[str, List[str]] = field(default_factory=dict)          # rel -> the student's lines
    exact: Set[Tuple[str, int]] = field(default_factory=set)   # (rel, student line) named by rewrite

    def rewrite(self, text: str) -> str:
        """`text` with every overlay path:line[:col] turned into the student's file:line[:col]."""
        for root in sorted(self.roots, key=len, reverse=True):    # impl/ inside its stage's root first
            files = self.roots[root]
            pattern = re.compile(re.escape(root.rstrip("/") + "/") + r"(?P<rel>[^\s:'\"()]+)(?::(?P<line>\d+))?")

            def repl(m: "re.Match[str]", files: Dict[str, Composed] = files) -> str:
                rel = m.group("rel")
                if m.group("line") is None:
                    return rel
                composed = files.get(rel)
                line = int(m.group("line"))
                if composed is None or not composed.lines.get(line):
                    return f"{rel}:{line}"
                if line in composed.exact:
                    self.exact.add((rel, composed.lines[line]))
                return f"{rel}:{composed.lines[line]}"

            text = pattern.sub(repl, text)
        return text

    def source_line(self, rel: str, line: int) -> Optional[str]:
        """The student's own line, when `rel:line` named one of their region's lines."""
        lines = self.student_lines.get(rel)
        if (rel, line) not in self.exact or lines is None or not 1 <= line <= len(lines):
            return None
        return lines[line - 1]
