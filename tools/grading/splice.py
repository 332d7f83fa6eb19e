"""Only the exercise regions come from a submission.

For each header of the reference that holds exercise regions, the grader reads the
student's copy of it, takes the lines between each pair of markers

    // RT_EXERCISE_BEGIN(stageNN: title)
    ...the student's lines...
    // RT_EXERCISE_END

and matches them to the reference's region by file, stage and title. Every other line of
the submission is ignored. A region's lines must stay inside the function body and name
only what an exercise needs: check_body lexes them as the compiler does (lexer.py: no
preprocessor directive, line splice, trigraph, control byte, brace that closes the
function, string or comment left open) and checks every name against the allow-list
(region_check.py, names.py: no process control, I/O, environment, `asm`, vendor attribute
or pointer cast). Such a region is refused, and its stage scores zero with a message
naming the line.

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
from . import lexer, region_check  # noqa: E402

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
    rel: str                                   # include/rt/intersection/sphere.hpp
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


def _shown(text: str) -> str:
    """`text` fit for a report: a control character as \\xNN or \\uNNNN, a byte that is not
    UTF-8 (a surrogate of errors="surrogateescape") as \\xNN."""
    def one(c: str) -> str:
        code = ord(c)
        if 0xDC80 <= code <= 0xDCFF:
            return f"\\x{code - 0xDC00:02x}"
        if c.isprintable() and not 0xD800 <= code <= 0xDFFF:
            return c
        return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"
    return "".join(one(c) for c in text)


def region_key(inside: str) -> Optional[Tuple[int, str]]:
    m = make_kit.BEGIN_INSIDE_RE.match(inside)
    return (int(m.group("stage")), m.group("title")) if m else None


def normalise(text: str) -> str:
    """The text with Windows line ends and a byte-order mark removed. A lone CR ends a line
    too, as it does for GCC and Clang, so that the grader's line numbers are the
    compiler's; the overlay is written from these lines with LF alone, so what the region
    scanner lexed is what the compiler reads."""
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
                             f"as the kit has it, found \"{_shown(inside)}\"; this region is ignored")
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
    line `file:line:col: expected ..., found ...; hint`: the lines lexed as the compiler
    reads them (lexer.py), their brackets paired, and every name they write on the
    allow-list (region_check.py, names.py)."""
    try:
        toks = lexer.tokens("\n".join(body), first_line)
        region_check.check(rel, toks, lexer.match_brackets(toks))
    except lexer.Refused as refused:
        return refused.refusal.message(rel)
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
            student: Optional[StudentFile]) -> Composed:
    """The reference's `rel` with each region's body chosen by `choice[index into regions]`:
    "reference", "stub" (the kit's not-done body) or a StudentRegion. Lines outside the
    regions are the reference's."""
    ref_lines = reference_text.split("\n")
    out: List[Tuple[str, int]] = []
    exact_lines: List[int] = []     # indexes into out
    order = sorted(range(len(regions)), key=lambda k: regions[k].begin_line)
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
