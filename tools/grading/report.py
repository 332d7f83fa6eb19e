"""What the grader writes: the table, Gradescope's results.json, JUnit XML and a batch's
grades.csv.

The table of the visible suites is what a student sees (results.json's top-level
`output`); the hidden suites appear only in their own test entries, whose visibility the
weights choose, and in the grader's own output (stdout, which Gradescope hides).
"""

from __future__ import annotations

import csv
import io
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Sequence

MAX_CASE_OUTPUT = 6000
STATUSES = ("passed", "failed", "crashed", "timeout", "not run")

# What a case prints, a compiler quotes or a member's name holds may be any bytes. XML 1.0
# allows no control character but tab, line feed and carriage return (NUL included), and
# neither XML nor JSON (nor UTF-8) holds a lone surrogate, which Python uses for a byte
# that is not UTF-8 (errors="surrogateescape"). Each becomes visible text: \xNN for a
# control character or such a byte, \uNNNN for another surrogate or U+FFFE/U+FFFF.
_NOT_TEXT_RE = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")
_NOT_CELL_RE = re.compile("[\x00-\x1f\x7f\ud800-\udfff\ufffe\uffff]")


def _shown_char(m: "re.Match[str]") -> str:
    code = ord(m.group(0))
    if 0xDC80 <= code <= 0xDCFF:          # a byte that is not UTF-8, as surrogateescape keeps it
        return f"\\x{code - 0xDC00:02x}"
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def clean_text(text: str) -> str:
    """The text with what XML 1.0, JSON and UTF-8 cannot hold written out as escapes;
    tabs and line breaks are kept."""
    return _NOT_TEXT_RE.sub(_shown_char, text)


def clean_cell(text: str) -> str:
    """One line of text for a cell of grades.csv: every control character (line breaks
    too) written out as an escape."""
    return _NOT_CELL_RE.sub(_shown_char, text)


def _clean_json(value: object) -> object:
    if isinstance(value, str):
        return clean_text(value)
    if isinstance(value, dict):
        return {clean_text(str(k)): _clean_json(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_clean_json(v) for v in value]
    return value


def clip(text: str, limit: int = MAX_CASE_OUTPUT) -> str:
    if len(text) <= limit:
        return text
    head = limit * 2 // 3
    return text[:head] + f"\n... ({len(text) - limit} characters left out) ...\n" + text[-(limit - head):]


@dataclass
class Case:
    name: str
    status: str = "not run"       # one of STATUSES
    output: str = ""
    seconds: float = 0.0


@dataclass
class Suite:
    stage: int
    hidden: bool
    title: str
    max_points: float
    targets: List[str]
    build_error: str = ""          # does not compile (the compiler's first error), or not graded
    refused: str = ""              # a region of this stage was refused (file:line:col: ...)
    cases: List[Case] = field(default_factory=list)
    note: str = ""                 # why no case ran, when none did
    remarks: List[str] = field(default_factory=list)   # for the student: regions not handed in ...

    @property
    def label(self) -> str:
        return f"stage{self.stage:02d}" + (".hidden" if self.hidden else "")

    @property
    def kind(self) -> str:
        return "hidden" if self.hidden else "visible"

    @property
    def passed(self) -> int:
        return sum(c.status == "passed" for c in self.cases)

    @property
    def graded_cases(self) -> List[Case]:
        """Every case of a stage suite: a stage suite holds only tests of its exercises (the
        library's own tests are in tests/library_*.cpp, which are never graded)."""
        return self.cases

    @property
    def points(self) -> float:
        counted = self.graded_cases
        if self.build_error or self.refused or not counted:
            return 0.0
        return round(self.max_points * sum(c.status == "passed" for c in counted) / len(counted), 2)

    @property
    def not_run(self) -> int:
        return sum(c.status == "not run" for c in self.cases)

    def remark(self) -> str:
        if self.refused:
            return "refused: " + self.refused.splitlines()[0]
        if self.build_error:
            first = self.build_error.splitlines()[0]
            return first if first.startswith("not ") else "does not compile: " + first
        bad = [c for c in self.cases if c.status != "passed"]
        if self.note:
            return self.note
        if not bad:
            return ""
        counts = {s: sum(c.status == s for c in bad) for s in STATUSES}
        return ", ".join(f"{n} {s}" for s, n in counts.items() if n)


def table(suites: Sequence[Suite]) -> str:
    """One row per suite: its cases, how many passed, the scored cases passed out of their
    number, and the points; then the total."""
    rows = [("stage", "suite", "cases", "passed", "scored", "points", "")]
    for s in suites:
        counted = s.graded_cases
        scored = f"{sum(c.status == 'passed' for c in counted)}/{len(counted)}" if s.cases else "-"
        rows.append((f"{s.stage:02d}", s.kind, str(len(s.cases)) if s.cases else "-", str(s.passed), scored,
                     f"{s.points:6.2f} / {s.max_points:6.2f}", s.remark()))
    total = sum(s.points for s in suites)
    total_max = sum(s.max_points for s in suites)
    rows.append(("total", "", str(sum(len(s.cases) for s in suites)), str(sum(s.passed for s in suites)), "",
                 f"{total:6.2f} / {total_max:6.2f}", ""))
    widths = [max(len(r[k]) for r in rows) for k in range(6)]
    return "\n".join("  ".join([r[k].ljust(widths[k]) for k in range(6)] + [r[6]]).rstrip() for r in rows)


def suite_output(s: Suite, mode_line: str = "") -> str:
    parts = [mode_line] if mode_line else []
    parts += s.remarks
    if s.refused:
        parts.append("Not graded: a region of this stage was refused (only the lines between the markers "
                     "are taken from your headers, and they must be plain C++):\n" + s.refused)
        return "\n".join(parts)
    if s.build_error:
        if s.build_error.startswith("not "):
            parts.append(s.build_error[0].upper() + s.build_error[1:])
        else:
            parts.append("Does not compile; the compiler's first error:\n" + s.build_error)
        return "\n".join(parts)
    if s.note:
        parts.append(s.note)
        return "\n".join(parts)
    failed = [c for c in s.cases if c.status != "passed"]
    counted = s.graded_cases
    parts.append(f"{s.passed} of {len(s.cases)} cases passed; {sum(c.status == 'passed' for c in counted)} of "
                 f"the {len(counted)} scored cases (those that test this stage's exercises) passed.")
    for c in failed:
        parts.append(f"--- {c.name}: {c.status}\n{clip(c.output, 2500).strip()}")
    return clip("\n\n".join(parts), 20000)


def gradescope_results(suites: Sequence[Suite], visibility: str, output: str, seconds: float,
                       mode_line: str = "") -> dict:
    """Gradescope's results.json: one test per suite. `output` (the top-level text students
    see) must name no hidden suite: the caller gives it the visible table only."""
    tests = []
    for s in suites:
        tests.append({
            "name": f"Stage {s.stage:02d} ({s.title}): {s.kind} tests",
            "number": f"{s.stage}.{2 if s.hidden else 1}",
            "score": s.points,
            "max_score": s.max_points,
            "status": "passed" if not (s.build_error or s.refused) and s.cases and s.passed == len(s.cases)
            else "failed",
            "output": suite_output(s, mode_line),
            "visibility": visibility if s.hidden else "visible",
        })
    return _clean_json({
        "score": round(sum(s.points for s in suites), 2),
        "execution_time": int(seconds),
        "output": output,
        "stdout_visibility": "hidden",
        "tests": tests,
    })


def junit(suites: Sequence[Suite]) -> ET.Element:
    def broken(s: Suite) -> bool:
        return bool(s.build_error or s.refused)

    root = ET.Element("testsuites", name="rt grading",
                      tests=str(sum(max(len(s.cases), 1 if broken(s) else 0) for s in suites)),
                      failures=str(sum((len(s.cases) - s.passed) + (1 if broken(s) else 0) for s in suites)))
    for s in suites:
        failures = len(s.cases) - s.passed + (1 if broken(s) else 0)
        node = ET.SubElement(root, "testsuite", name=s.label, tests=str(len(s.cases) or 1),
                             failures=str(failures), time=f"{sum(c.seconds for c in s.cases):.3f}")
        properties = ET.SubElement(node, "properties")
        properties.append(ET.Element("property", name="points", value=f"{s.points}"))
        properties.append(ET.Element("property", name="max_points", value=f"{s.max_points}"))
        if broken(s):
            case = ET.SubElement(node, "testcase", classname=s.label, name="build")
            failure = ET.SubElement(case, "failure", message="refused" if s.refused else "does not compile")
            failure.text = s.refused or s.build_error
            continue
        for c in s.cases:
            case = ET.SubElement(node, "testcase", classname=s.label, name=c.name, time=f"{c.seconds:.3f}")
            if c.status != "passed":
                failure = ET.SubElement(case, "failure", message=c.status)
                failure.text = c.output
            else:
                ET.SubElement(case, "system-out").text = c.output
    for element in root.iter():     # whatever bytes a case printed, the XML stays well-formed
        if element.text:
            element.text = clean_text(element.text)
        for key, value in element.attrib.items():
            element.attrib[key] = clean_text(value)
    return root


def junit_bytes(suites: Sequence[Suite]) -> bytes:
    tree = ET.ElementTree(junit(suites))
    if hasattr(ET, "indent"):  # Python 3.9+
        ET.indent(tree)
    buffer = io.BytesIO()
    tree.write(buffer, encoding="utf-8", xml_declaration=True)
    return buffer.getvalue()


def grades_csv(rows: Sequence[Dict[str, object]], stages: Sequence[int]) -> bytes:
    """One line per student: the points of each stage (visible and hidden together), the
    total and the status."""
    out = io.StringIO()
    columns = ["student"] + [f"stage{s:02d}" for s in stages] + ["total", "status"]
    writer = csv.DictWriter(out, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({k: clean_cell(str(row.get(k, ""))) for k in columns})
    return out.getvalue().encode("utf-8")


def stage_points(suites: Sequence[Suite]) -> Dict[int, float]:
    points: Dict[int, float] = {}
    for s in suites:
        points[s.stage] = round(points.get(s.stage, 0.0) + s.points, 2)
    return points
