#!/usr/bin/env python3
"""grade.py - grade a student's rt stage by stage.

    python3 tools/grade.py SUBMISSION [--hidden DIR] [--weights tools/weights.json]
                           [--out DIR] [--results-json FILE] [--junit FILE]

SUBMISSION is a folder or a .zip / .tar.gz / .tgz / .tar archive holding the student's
include/rt (alone, or inside a whole repository). The grader
1. copies the reference repository (the one holding this script, or --reference) without
   its instructor-only files and with every exercise stripped, then puts the student's
   headers over its include/rt (a header the student did not hand in stays "not done");
2. adds the instructor's hidden suites from --hidden DIR (stageNN_<name>.cpp files, and
   their data in DIR/data, never part of a kit);
3. builds each stage's test executable on its own: a stage that does not compile scores
   zero, with the compiler's first error in its output, and costs no other stage anything;
4. runs every test case in a process of its own, with a per-case and a per-stage time
   limit, so a crash or a hang fails that case (or the rest of that stage) and nothing else;
5. scores each stage: its points (weights file) times the fraction of its cases passed, for
   the visible and the hidden suites separately; and writes a table to the terminal, JUnit
   XML and a Gradescope results.json.

The weights file is JSON, documented in docs/instructor-guide.md:
    {"stage_timeout_seconds": 120, "case_timeout_seconds": 60,
     "hidden_visibility": "after_published",
     "default": {"visible": 10, "hidden": 0},
     "stages": {"01": {"visible": 10}, "03": {"visible": 10, "hidden": 5}}}

Exit code 0 when the submission was graded (whatever its score), 1 when the grader could
not run (no cmake, a broken reference), 2 for a bad command line. Python 3 standard
library only.
"""

from __future__ import annotations

import argparse
import io
import json
import os
import re
import shutil
import signal
import stat
import subprocess
import sys
import tarfile
import tempfile
import time
import zipfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Dict, List, Optional, Sequence, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_kit  # noqa: E402  (the sibling module)

HEADER_SUFFIXES = (".hpp", ".h", ".hh", ".hxx", ".inl", ".ipp", ".tpp")
MAX_SUBMISSION_BYTES = 64 * 1024 * 1024
MAX_CASE_OUTPUT = 6000
VISIBILITIES = ("hidden", "after_due_date", "after_published", "visible")


class GradeError(Exception):
    """The grader itself cannot run (exit 1)."""


class SubmissionError(Exception):
    """The submission cannot be graded: it scores zero with this message."""


# --------------------------------------------------------------------------
# Weights
# --------------------------------------------------------------------------

@dataclass
class Weights:
    stage_timeout: float = 120
    case_timeout: float = 60
    hidden_visibility: str = "after_published"
    default_visible: float = 10
    default_hidden: float = 0
    stages: Dict[int, Dict[str, float]] = field(default_factory=dict)

    def points(self, stage: int, suite: str) -> float:
        entry = self.stages.get(stage, {})
        return float(entry.get(suite, self.default_visible if suite == "visible" else self.default_hidden))


def load_weights(path: Path) -> Weights:
    where = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise GradeError(f"{where}: expected a readable weights file, found {e.strerror}; "
                         f"see docs/instructor-guide.md")
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise GradeError(f"{where}:{e.lineno}:{e.colno}: expected JSON, found {e.msg}")

    def fail(key: str, expected: str, found: object) -> GradeError:
        line = next((k + 1 for k, l in enumerate(text.splitlines()) if f'"{key}"' in l), 1)
        return GradeError(f"{where}:{line}: expected {expected} for \"{key}\", found {json.dumps(found)}")

    def number(key: str, value: object) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0:
            raise fail(key, "a number >= 0", value)
        return float(value)

    if not isinstance(data, dict):
        raise GradeError(f"{where}:1:1: expected a JSON object, found {type(data).__name__}")
    w = Weights()
    known = {"stage_timeout_seconds", "case_timeout_seconds", "hidden_visibility", "default", "stages"}
    for key in data:
        if key not in known and not key.startswith("//"):
            raise fail(key, "one of " + ", ".join(sorted(known)) + " (or a \"//\" comment)", key)
    if "stage_timeout_seconds" in data:
        w.stage_timeout = number("stage_timeout_seconds", data["stage_timeout_seconds"])
    if "case_timeout_seconds" in data:
        w.case_timeout = number("case_timeout_seconds", data["case_timeout_seconds"])
    if "hidden_visibility" in data:
        if data["hidden_visibility"] not in VISIBILITIES:
            raise fail("hidden_visibility", "one of " + ", ".join(VISIBILITIES), data["hidden_visibility"])
        w.hidden_visibility = data["hidden_visibility"]

    def suite_points(key: str, entry: object) -> Dict[str, float]:
        if not isinstance(entry, dict):
            raise fail(key, '{"visible": points, "hidden": points}', entry)
        out = {}
        for suite, value in entry.items():
            if suite.startswith("//"):
                continue
            if suite not in ("visible", "hidden"):
                raise fail(key, '"visible" or "hidden"', suite)
            out[suite] = number(key, value)
        return out

    if "default" in data:
        d = suite_points("default", data["default"])
        w.default_visible = d.get("visible", w.default_visible)
        w.default_hidden = d.get("hidden", w.default_hidden)
    stages = data.get("stages", {})
    if not isinstance(stages, dict):
        raise fail("stages", 'an object {"01": {...}, ...}', stages)
    for key, entry in stages.items():
        if key.startswith("//"):
            continue
        if not re.fullmatch(r"[0-9]{2}", key):
            raise fail(key, "a two-digit stage such as \"03\"", key)
        w.stages[int(key)] = suite_points(key, entry)
    return w


# --------------------------------------------------------------------------
# The submission
# --------------------------------------------------------------------------

def _safe_member(name: str) -> Optional[PurePosixPath]:
    path = PurePosixPath(name.replace("\\", "/"))
    if path.is_absolute() or ".." in path.parts or not path.parts:
        return None
    if path.parts[0] == "__MACOSX":
        return None
    return path


def unpack(submission: Path, into: Path) -> None:
    """Copies or extracts the submission into `into`: regular files only, no links,
    no paths outside it, at most MAX_SUBMISSION_BYTES."""
    into.mkdir(parents=True, exist_ok=True)
    total = 0

    def account(size: int) -> None:
        nonlocal total
        total += size
        if total > MAX_SUBMISSION_BYTES:
            raise SubmissionError(f"the submission is larger than {MAX_SUBMISSION_BYTES // (1024 * 1024)} MiB; "
                                  f"hand in include/rt only")

    if submission.is_dir():
        for dirpath, dirnames, filenames in os.walk(submission):
            dirnames[:] = [d for d in dirnames if d not in make_kit.ALWAYS_SKIPPED_DIRS
                           and not make_kit.BUILD_DIR_RE.match(d)]
            for name in filenames:
                source = Path(dirpath, name)
                if source.is_symlink() or not source.is_file():
                    continue
                account(source.stat().st_size)
                destination = into / source.relative_to(submission)
                destination.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(source, destination)
        return
    if not submission.is_file():
        raise SubmissionError(f"{submission}: no such file or folder")
    name = submission.name.lower()
    if name.endswith(".zip"):
        try:
            with zipfile.ZipFile(submission) as archive:
                for info in archive.infolist():
                    mode = (info.external_attr >> 16) & 0o170000
                    target = _safe_member(info.filename)
                    if info.is_dir() or target is None or mode == stat.S_IFLNK:
                        continue
                    account(info.file_size)
                    destination = into.joinpath(*target.parts)
                    destination.parent.mkdir(parents=True, exist_ok=True)
                    with archive.open(info) as src, open(destination, "wb") as dst:
                        shutil.copyfileobj(src, dst)
        except zipfile.BadZipFile as e:
            raise SubmissionError(f"{submission.name}: not a readable zip archive ({e})")
        return
    if name.endswith((".tar.gz", ".tgz", ".tar", ".tar.bz2", ".tar.xz")):
        try:
            with tarfile.open(submission) as archive:
                for member in archive:
                    target = _safe_member(member.name)
                    if not member.isfile() or target is None:
                        continue  # links, devices, folders and paths outside are skipped
                    account(member.size)
                    destination = into.joinpath(*target.parts)
                    destination.parent.mkdir(parents=True, exist_ok=True)
                    src = archive.extractfile(member)
                    if src is None:
                        continue
                    with src, open(destination, "wb") as dst:
                        shutil.copyfileobj(src, dst)
        except tarfile.TarError as e:
            raise SubmissionError(f"{submission.name}: not a readable tar archive ({e})")
        return
    raise SubmissionError(f"{submission.name}: expected a folder, .zip, .tar.gz, .tgz or .tar, "
                          f"found another kind of file")


def find_rt_folder(root: Path, reference_headers: Sequence[str]) -> Path:
    """The submission's rt header folder: include/rt if there is one, else the
    shallowest folder named rt with headers, else a folder holding rt's headers."""
    candidates: List[Tuple[int, int, str, Path]] = []
    known = set(reference_headers)
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        here = Path(dirpath)
        headers = [f for f in filenames if f.endswith(HEADER_SUFFIXES)]
        if not headers:
            continue
        depth = len(here.relative_to(root).parts)
        if here.name == "rt" and here.parent.name == "include":
            candidates.append((0, depth, str(here), here))
        elif here.name == "rt":
            candidates.append((1, depth, str(here), here))
        elif known & set(headers):
            candidates.append((2, depth, str(here), here))
    if not candidates:
        raise SubmissionError("no include/rt folder (or rt's headers) found in the submission; "
                              "hand in your include/rt folder, or the whole repository")
    return min(candidates)[3]


# --------------------------------------------------------------------------
# Building and running
# --------------------------------------------------------------------------

def run(args: Sequence[str], cwd: Optional[Path] = None, timeout: Optional[float] = None) -> Tuple[int, str]:
    try:
        p = subprocess.run(list(args), cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout, start_new_session=True)
        return p.returncode, p.stdout.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as e:
        return -1, (e.stdout or b"").decode("utf-8", "replace") + f"\n(stopped after {timeout:.0f} s)"


def first_compiler_error(output: str, strip_prefixes: Sequence[str]) -> str:
    """The compiler's first error and the few lines that explain it."""
    lines = output.splitlines()
    for k, line in enumerate(lines):
        if re.search(r"\b(fatal )?error\b:|undefined reference|\(stopped after", line):
            block = [line]
            for extra in lines[k + 1:k + 6]:
                if re.match(r"^(\S+:\d+:\d+: (error|warning)|FAILED:|ninja:|\[\d+/\d+\]|make)", extra):
                    break
                block.append(extra)
            text = "\n".join(block)
            break
    else:
        tail = [l for l in lines if l.strip()][-8:]
        text = "\n".join(tail) if tail else "(the build printed nothing)"
    for prefix in strip_prefixes:
        text = text.replace(prefix.rstrip("/") + "/", "")
    return text


def _limit_resources(memory_mb: int):
    def apply() -> None:
        try:
            import resource
            if memory_mb > 0:
                limit = memory_mb * 1024 * 1024
                resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
            resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        except (ImportError, ValueError, OSError):
            pass
    return apply


def run_case(command: Sequence[str], cwd: Optional[str], timeout: float, memory_mb: int) -> Tuple[str, str, float]:
    """Runs one test case in its own process group; returns (status, output, seconds)
    with status passed, failed, crashed or timeout."""
    t0 = time.monotonic()
    try:
        p = subprocess.Popen(list(command), cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, start_new_session=True,
                             preexec_fn=_limit_resources(memory_mb) if os.name == "posix" else None)
    except OSError as e:
        return "crashed", f"could not start the test: {e}", 0.0
    try:
        out, _ = p.communicate(timeout=max(timeout, 0.1))
    except subprocess.TimeoutExpired:
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except OSError:
            p.kill()
        out, _ = p.communicate()
        text = out.decode("utf-8", "replace")
        return "timeout", text + f"\n(stopped: still running after {timeout:.0f} s)", time.monotonic() - t0
    text = out.decode("utf-8", "replace")
    seconds = time.monotonic() - t0
    if p.returncode == 0:
        return "passed", text, seconds
    if p.returncode < 0:
        try:
            name = signal.Signals(-p.returncode).name
        except ValueError:
            name = f"signal {-p.returncode}"
        return "crashed", text + f"\n(crashed: {name})", seconds
    return "failed", text, seconds


def clip(text: str, limit: int = MAX_CASE_OUTPUT) -> str:
    if len(text) <= limit:
        return text
    head = limit * 2 // 3
    return text[:head] + f"\n... ({len(text) - limit} characters left out) ...\n" + text[-(limit - head):]


# --------------------------------------------------------------------------
# Grading
# --------------------------------------------------------------------------

@dataclass
class Case:
    name: str
    status: str = "not run"
    output: str = ""
    seconds: float = 0.0


@dataclass
class Suite:
    stage: int
    hidden: bool
    title: str
    max_points: float
    targets: List[str]
    build_error: str = ""
    cases: List[Case] = field(default_factory=list)
    note: str = ""

    @property
    def label(self) -> str:
        return f"stage{self.stage:02d}" + (".hidden" if self.hidden else "")

    @property
    def passed(self) -> int:
        return sum(c.status == "passed" for c in self.cases)

    @property
    def graded_cases(self) -> List[Case]:
        """The cases that measure the student's work: every case of a stage suite, since a
        stage suite holds only tests of its exercises (the library's own tests are in the
        tests/library_*.cpp suites, which are never graded)."""
        return self.cases

    @property
    def points(self) -> float:
        counted = self.graded_cases
        if self.build_error or not counted:
            return 0.0
        return round(self.max_points * sum(c.status == "passed" for c in counted) / len(counted), 2)


def stage_titles(root: Path) -> Dict[int, str]:
    titles = {}
    for stage, files in make_kit.known_stages(root).items():
        titles[stage] = ", ".join(Path(f).stem[8:].replace("_", " ") for f in files)
    return titles


def make_suites(reference: Path, weights: Weights, hidden_dir: Optional[Path]) -> List[Suite]:
    """The suites to grade, from the reference's tests and the hidden folder alone, so a
    submission that builds nothing still shows every suite it could have scored in."""
    titles = stage_titles(reference)
    stages = make_kit.known_stages(reference)
    suites = [Suite(stage, False, titles[stage], weights.points(stage, "visible"),
                    [f"test_{Path(f).stem}" for f in stages[stage]]) for stage in sorted(stages)]
    if hidden_dir is not None:
        hidden_files: Dict[int, List[str]] = {}
        for f in sorted(hidden_dir.glob("stage[0-9][0-9]_*.cpp")):
            hidden_files.setdefault(int(f.name[5:7]), []).append(f"test_hidden_{f.stem}")
        for stage, targets in sorted(hidden_files.items()):
            suites.append(Suite(stage, True, titles.get(stage, "hidden"), weights.points(stage, "hidden"), targets))
    suites.sort(key=lambda x: (x.stage, x.hidden))
    return suites


def overlay(rt_folder: Path, src: Path) -> List[str]:
    """Copies the submission's headers over src/include/rt; returns their paths."""
    handed_in = []
    for dirpath, _, filenames in os.walk(rt_folder):
        for name in sorted(filenames):
            if not name.endswith(HEADER_SUFFIXES):
                continue
            source = Path(dirpath, name)
            rel = source.relative_to(rt_folder)
            destination = src / "include" / "rt" / rel
            destination.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(source, destination)
            handed_in.append(rel.as_posix())
    return handed_in


def build_and_run(src: Path, build: Path, hidden: Path, suites: List[Suite], weights: Weights,
                  args: argparse.Namespace, strip: Sequence[str]) -> None:
    """Configures src once, builds each suite's executables on its own and runs each of
    their cases in a process of its own; fills in the suites' build errors and cases."""
    shutil.rmtree(build, ignore_errors=True)
    configure = ["cmake", "-S", str(src), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                 "-DRT_WERROR=OFF", "-DRT_BUILD_STAGES=OFF", "-DRT_INSTALL=OFF",
                 f"-DRT_HIDDEN_TESTS_DIR={hidden}"]
    if shutil.which("ninja"):
        configure += ["-G", "Ninja"]
    code, out = run(configure, timeout=args.build_timeout)
    if code != 0:
        error = first_compiler_error(out, strip)
        for s in suites:
            s.build_error = "configure failed: " + error
        return
    code, out = run(["cmake", "--build", str(build), "--target", "rt_test_main", "-j", str(args.jobs)],
                    timeout=args.build_timeout)
    if code != 0:
        raise GradeError("the reference's doctest runner does not build:\n" + first_compiler_error(out, strip))
    for s in suites:
        log(f"grade: building {s.label} ({', '.join(s.targets)})")
        code, out = run(["cmake", "--build", str(build), "--target", *s.targets, "-j", str(args.jobs)],
                        timeout=args.build_timeout)
        if code != 0:
            s.build_error = first_compiler_error(out, strip)

    code, out = run(["ctest", "--test-dir", str(build), "--show-only=json-v1"], timeout=120)
    try:
        listing = json.loads(out[out.index("{"):]) if code == 0 else {"tests": []}
    except ValueError:
        listing = {"tests": []}
    by_label: Dict[str, List[dict]] = {}
    for test in listing.get("tests", []):
        m = re.match(r"^(stage[0-9]{2})\.(hidden\.)?(.*)$", test.get("name", ""))
        if m:
            by_label.setdefault(m.group(1) + (".hidden" if m.group(2) else ""), []).append(test)
    for s in suites:
        if s.build_error:
            continue
        tests = by_label.get(s.label, [])
        if not tests:
            s.note = "no test case was found"
            continue
        deadline = time.monotonic() + weights.stage_timeout
        log(f"grade: running {s.label}: {len(tests)} cases")
        for test in tests:
            case = Case(test["name"].split(".", 2 if s.hidden else 1)[-1])
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                case.status = "timeout"
                case.output = (f"not run: the stage's time limit of {weights.stage_timeout:.0f} s "
                               f"was used up by the cases before it")
            else:
                cwd = next((p.get("value") for p in test.get("properties", [])
                            if p.get("name") == "WORKING_DIRECTORY"), None)
                case.status, output, case.seconds = run_case(
                    test["command"], cwd, min(weights.case_timeout, remaining), args.memory_mb)
                for prefix in strip:
                    output = output.replace(prefix.rstrip("/") + "/", "")
                case.output = clip(output)
            s.cases.append(case)


def grade(args: argparse.Namespace) -> Tuple[List[Suite], str, Weights]:
    """Grades the submission; returns the suites, a note for the whole submission and the weights."""
    reference = Path(args.reference).resolve()
    weights = load_weights(Path(args.weights) if args.weights else reference / "tools" / "weights.json")
    if args.stage_timeout is not None:
        weights.stage_timeout = args.stage_timeout
    if args.case_timeout is not None:
        weights.case_timeout = args.case_timeout
    for tool in ("cmake", "ctest"):
        if shutil.which(tool) is None:
            raise GradeError(f"expected {tool} on PATH, found none; install cmake")
    work = Path(args.work).resolve()
    src, build, sub, hidden = work / "src", work / "build", work / "submission", work / "hidden"
    for d in (src, build, sub, hidden):
        shutil.rmtree(d, ignore_errors=True)
    hidden_dir: Optional[Path] = None
    if args.hidden:
        hidden_dir = Path(args.hidden).resolve()
        if not hidden_dir.is_dir():
            raise GradeError(f"{hidden_dir}: expected a folder of hidden suites, found none")
        shutil.copytree(hidden_dir, hidden)

    suites = make_suites(reference, weights, hidden_dir)
    stages = make_kit.known_stages(reference)
    notes = [f"stage {stage:02d} is in the weights file but has no tests: not graded"
             for stage in sorted(set(weights.stages) - set(stages))]
    try:
        plan = make_kit.plan_kit(reference, set(stages))
    except make_kit.KitError as e:
        raise GradeError("the reference's exercise markers are invalid:\n" + "\n".join(e.messages))
    if args.calibrate:
        return suites, "nothing to calibrate: every case of a stage suite tests an exercise", weights

    # the submission's headers over a stripped copy of the reference
    reference_headers = [Path(f).name for f in plan.files if f.startswith("include/rt/")]
    try:
        unpack(Path(args.submission), sub)
        rt_folder = find_rt_folder(sub, reference_headers)
    except SubmissionError as e:
        for s in suites:
            s.build_error = f"not graded: {e}"
        return suites, "\n".join(notes + [str(e)]), weights
    make_kit.write_tree(reference, plan, src)
    handed_in = overlay(rt_folder, src)
    notes.append(f"graded {len(handed_in)} headers from {rt_folder.relative_to(sub).as_posix() or '.'}/ "
                 f"of the submission")
    missing = sorted({f[len("include/rt/"):] for f in plan.files if f.startswith("include/rt/")} - set(handed_in))
    if missing:
        notes.append("not handed in (graded as not done): " + ", ".join(missing))
    build_and_run(src, build, hidden, suites, weights, args, [str(src), str(hidden), str(work)])
    return suites, "\n".join(notes), weights


# --------------------------------------------------------------------------
# Reports
# --------------------------------------------------------------------------

def table(suites: List[Suite]) -> str:
    """One row per suite: its cases, how many passed, the scored cases passed out of
    their number, and the points."""
    rows = [("stage", "suite", "cases", "passed", "scored", "points", "")]
    for s in suites:
        if s.build_error:
            remark = s.build_error.splitlines()[0]
            if not remark.startswith("not graded"):
                remark = "does not compile: " + remark
        else:
            bad = [c for c in s.cases if c.status != "passed"]
            kinds = sorted({c.status for c in bad})
            remark = s.note or (f"{len(bad)} {'/'.join(kinds)}" if bad else "")
        counted = s.graded_cases
        scored = f"{sum(c.status == 'passed' for c in counted)}/{len(counted)}" if s.cases else "-"
        rows.append((f"{s.stage:02d}", "hidden" if s.hidden else "visible",
                     str(len(s.cases)) if s.cases else "-", str(s.passed), scored,
                     f"{s.points:6.2f} / {s.max_points:6.2f}", remark))
    total = sum(s.points for s in suites)
    total_max = sum(s.max_points for s in suites)
    rows.append(("total", "", str(sum(len(s.cases) for s in suites)), str(sum(s.passed for s in suites)), "",
                 f"{total:6.2f} / {total_max:6.2f}", ""))
    widths = [max(len(r[k]) for r in rows) for k in range(6)]
    lines = []
    for r in rows:
        cells = [r[k].ljust(widths[k]) for k in range(6)] + [r[6]]
        lines.append("  ".join(cells).rstrip())
    return "\n".join(lines)


def suite_output(s: Suite) -> str:
    if s.build_error:
        return "Does not compile; the compiler's first error:\n" + s.build_error
    if s.note:
        return s.note
    failed = [c for c in s.cases if c.status != "passed"]
    counted = s.graded_cases
    head = (f"{s.passed} of {len(s.cases)} cases passed; {sum(c.status == 'passed' for c in counted)} of the "
            f"{len(counted)} scored cases (those that test this stage's exercises) passed.")
    if not failed:
        return head
    parts = [head]
    for c in failed:
        parts.append(f"--- {c.name}: {c.status}\n{clip(c.output, 2500).strip()}")
    return clip("\n\n".join(parts), 20000)


def gradescope_results(suites: List[Suite], weights_visibility: str, note: str, seconds: float) -> dict:
    tests = []
    for s in suites:
        tests.append({
            "name": f"Stage {s.stage:02d} ({s.title}): {'hidden' if s.hidden else 'visible'} tests",
            "number": f"{s.stage}.{2 if s.hidden else 1}",
            "score": s.points,
            "max_score": s.max_points,
            "status": "passed" if not s.build_error and s.cases and s.passed == len(s.cases) else "failed",
            "output": suite_output(s),
            "visibility": weights_visibility if s.hidden else "visible",
        })
    return {
        "score": round(sum(s.points for s in suites), 2),
        "execution_time": int(seconds),
        "output": note,
        "stdout_visibility": "hidden",
        "tests": tests,
    }


def junit(suites: List[Suite]) -> ET.Element:
    root = ET.Element("testsuites", name="rt grading",
                      tests=str(sum(max(len(s.cases), 1 if s.build_error else 0) for s in suites)),
                      failures=str(sum((len(s.cases) - s.passed) + (1 if s.build_error else 0) for s in suites)))
    for s in suites:
        failures = len(s.cases) - s.passed + (1 if s.build_error else 0)
        node = ET.SubElement(root, "testsuite", name=s.label, tests=str(len(s.cases) or 1),
                             failures=str(failures), time=f"{sum(c.seconds for c in s.cases):.3f}")
        ET.SubElement(node, "properties")
        node.find("properties").append(ET.Element("property", name="points", value=f"{s.points}"))
        node.find("properties").append(ET.Element("property", name="max_points", value=f"{s.max_points}"))
        if s.build_error:
            case = ET.SubElement(node, "testcase", classname=s.label, name="build")
            failure = ET.SubElement(case, "failure", message="does not compile")
            failure.text = s.build_error
            continue
        for c in s.cases:
            case = ET.SubElement(node, "testcase", classname=s.label, name=c.name, time=f"{c.seconds:.3f}")
            if c.status != "passed":
                failure = ET.SubElement(case, "failure", message=c.status)
                failure.text = c.output
            else:
                ET.SubElement(case, "system-out").text = c.output
    return root


def write_atomically(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".tmp-", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def log(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description="Grade a student's rt stage by stage.")
    parser.add_argument("submission", nargs="?", help="a folder or a .zip/.tar.gz/.tgz/.tar of include/rt or the repository")
    parser.add_argument("--reference", default=str(make_kit.DEFAULT_SOURCE),
                        help="the reference repository (default: the one holding this script)")
    parser.add_argument("--hidden", help="folder of hidden suites stageNN_<name>.cpp (and data/)")
    parser.add_argument("--weights", help="weights file (default: <reference>/tools/weights.json)")
    parser.add_argument("--out", default="grade-results", help="folder for results.json and junit.xml")
    parser.add_argument("--results-json", help="where to write the Gradescope results (default: OUT/results.json)")
    parser.add_argument("--junit", help="where to write the JUnit XML (default: OUT/junit.xml)")
    parser.add_argument("--work", help="build folder (default: a temporary folder, removed afterwards)")
    parser.add_argument("--stage-timeout", type=float, help="seconds for all of one stage's cases (overrides weights)")
    parser.add_argument("--case-timeout", type=float, help="seconds for one case (overrides weights)")
    parser.add_argument("--build-timeout", type=float, default=600, help="seconds for configuring or one build")
    parser.add_argument("--memory-mb", type=int, default=4096, help="address-space limit per test case (0: none)")
    parser.add_argument("--jobs", type=int, default=2)
    # No baseline is needed any more (a stage suite tests only its exercises): --cache and
    # --calibrate are accepted so that existing scripts (tools/gradescope) keep working.
    parser.add_argument("--cache", help="accepted and unused (there is no stripped-reference baseline to cache)")
    parser.add_argument("--calibrate", action="store_true",
                        help="accepted for old setup scripts: checks the reference's markers and exits")
    args = parser.parse_args(argv if argv is not None else None)
    if args.calibrate and not args.cache:
        parser.error("--calibrate needs --cache DIR")
    if not args.calibrate and not args.submission:
        parser.error("give the submission: a folder or an archive")

    out = Path(args.out)
    results_path = Path(args.results_json) if args.results_json else out / "results.json"
    junit_path = Path(args.junit) if args.junit else out / "junit.xml"
    temporary = None
    if not args.work:
        temporary = tempfile.mkdtemp(prefix="rt-grade-")
        args.work = temporary
    started = time.monotonic()
    try:
        suites, note, weights = grade(args)
        visibility = weights.hidden_visibility
        if args.calibrate:
            print(note)
            return 0
        text = table(suites)
        results = gradescope_results(suites, visibility, text + ("\n\n" + note if note else ""),
                                     time.monotonic() - started)
        write_atomically(results_path, (json.dumps(results, indent=2) + "\n").encode("utf-8"))
        tree = ET.ElementTree(junit(suites))
        if hasattr(ET, "indent"):  # Python 3.9+
            ET.indent(tree)
        buffer = io.BytesIO()
        tree.write(buffer, encoding="utf-8", xml_declaration=True)
        write_atomically(junit_path, buffer.getvalue())
        print(text + ("\n" + note if note else ""), flush=True)
        log(f"grade: wrote {results_path} and {junit_path}")
        return 0
    except GradeError as e:
        print(f"grade: {e}", file=sys.stderr)
        return 1
    finally:
        if temporary:
            shutil.rmtree(temporary, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
