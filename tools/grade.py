#!/usr/bin/env python3
"""grade.py - grade a student's rt stage by stage.

    python3 tools/grade.py SUBMISSION [--hidden DIR] [--out DIR] [--cache DIR] [--stages 3,4]
                           [--cumulative] [--budget 600] [--jobs 2]
    python3 tools/grade.py --batch FOLDER --out DIR [--jobs N] ...   (writes DIR/grades.csv)
    python3 tools/grade.py --calibrate --cache DIR [--hidden DIR] [--stages 3,4]

SUBMISSION is a folder or a .zip / .tar.gz / .tgz / .tar archive holding the student's
include/rt (alone, or inside a whole repository). The grader
1. takes only the exercise regions of the submission (the lines between the
   RT_EXERCISE_BEGIN and RT_EXERCISE_END markers, matched to the reference's by file, stage
   and title); every other line of the submission is ignored. Each region is lexed as the
   compiler reads it and may name only what an exercise needs (grading/lexer.py,
   region_check.py, names.py): a region that names anything else is refused, its stage
   scores zero, with a message naming the line;
2. builds, for each stage, a server: the kit's headers with the student's regions of the
   stage (and of the stages before it, --cumulative), compiled and run as an unprivileged
   test user (--run-as, default rtgrader, one uid per batch slot) that cannot read the
   reference or the hidden suites; several stages share one build when they compile;
3. runs every test case in a judge (grading/judge/, built once per cache with the
   reference's code, --cache, --calibrate): the judge holds the assertions and the
   expected values, and each call into a student's function crosses a pipe to the server,
   which runs confined by seccomp. The verdict is the judge's alone: a case passes only
   when the judge saw every assertion the reference's run of it makes, so nothing the
   student's process prints, or how it ends, can pass a case;
4. gives each stage its own compile and run limits, and all of it a time budget (--budget);
5. scores each stage: its points (weights file) times the fraction of its cases passed, for
   the visible and the hidden suites separately; and writes a table, JUnit XML and a
   Gradescope results.json (whose top-level output names only the visible suites).

The weights file is JSON, documented in docs/instructor-guide.md. Exit code 0 when the
submission was graded (whatever its score), 1 when the grader could not run (no cmake, a
broken reference), 2 for a bad command line. Python 3 standard library only.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import json
import os
import re
import shutil
import sys
import tempfile
import threading
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_kit  # noqa: E402  (the sibling module)
from grading.batch import grade_batch  # noqa: E402
from grading.cache import Cache, Reference, Slot, _flock  # noqa: E402
from grading.common import Deadline, GradeError, SubmissionError, log, parse_stages, write_atomically  # noqa: E402
from grading.report import (Case, Suite, clip, grades_csv, gradescope_results, junit,  # noqa: E402,F401
                            junit_bytes, stage_points, table)
from grading import judge, names  # noqa: E402
from grading.common import run  # noqa: E402
from grading.sandbox import (Processors, TestUser, UidBlock, choose_user, claim_uid_block, reap_all,  # noqa: E402
                             run_judged, slot_user)
from grading.splice import LineMaps, StudentFile, outside_differences, normalise, read_student_file  # noqa: E402
from grading.submission import HEADER_SUFFIXES, find_rt_folder, reference_path, unpack  # noqa: E402,F401
from grading.weights import VISIBILITIES, Weights, load_weights  # noqa: E402,F401

DEFAULT_BUDGET = 600
# A server of several stages builds in seconds; one that takes longer than this (a
# compile-time bomb in one of them) is given up for a build of each stage alone.
GROUP_COMPILE_SECONDS = 60
MAX_NOTES = 12


# --------------------------------------------------------------------------
# What a grading run shares
# --------------------------------------------------------------------------

@dataclass
class Context:
    reference: Reference
    weights: Weights
    stages: List[int]                 # the stages graded
    cache: Cache
    user: TestUser
    cumulative: bool
    budget: float
    memory_mb: int
    instructor_notes: List[str] = field(default_factory=list)
    # each running case's judge and server share a processor: a call's handover is then a
    # switch of task, not a wake-up across processors
    processors: Processors = field(default_factory=Processors)
    # the uids this run's slots run as, no other grading run's (when the grader is root)
    uid_block: Optional[UidBlock] = None

    @property
    def mode_line(self) -> str:
        if self.cumulative:
            return ("Graded cumulatively: each stage's tests ran with your code of that stage and the stages "
                    "before it, so a mistake in one stage can fail the stages that use it.")
        return ("Each stage judged alone: stage N's tests ran with your code of stage N and the reference's "
                "code of every other stage, so a mistake in one stage costs that stage only.")


@dataclass
class Outcome:
    suites: List[Suite]
    notes: List[str] = field(default_factory=list)        # for the student
    status: str = "graded"
    seconds: float = 0.0


def make_suites(ctx: Context) -> List[Suite]:
    """The suites to grade, from the reference and the hidden folder alone, so a submission
    that builds nothing still shows every suite it could have scored in."""
    titles = ctx.reference.titles()
    suites: Dict[Tuple[int, bool], Suite] = {}
    for t in ctx.cache.targets(set(ctx.stages)):
        key = (t.stage, t.hidden)
        if key not in suites:
            suites[key] = Suite(t.stage, t.hidden, titles[t.stage],
                                ctx.weights.points(t.stage, "hidden" if t.hidden else "visible"), [])
        suites[key].targets.append(t.name)
    return [suites[k] for k in sorted(suites)]


# --------------------------------------------------------------------------
# Compiler messages
# --------------------------------------------------------------------------

def first_compiler_error(output: str, strip_prefixes: Sequence[str], maps: Optional[LineMaps] = None) -> str:
    """The compiler's first error and the few lines that explain it, in the student's own
    file and line numbers, with the student's line shown under it."""
    if maps is not None:
        output = maps.rewrite(output)
    for prefix in strip_prefixes:
        output = output.replace(prefix.rstrip("/") + "/", "")
    lines = output.splitlines()
    for k, line in enumerate(lines):
        if re.search(r"\b(fatal )?error\b:|undefined reference|\(stopped after|time budget", line):
            block = [line]
            m = re.match(r"^(?P<rel>[^\s:]+):(?P<line>\d+):(?P<col>\d+): ", line)
            if maps is not None and m:
                source = maps.source_line(m.group("rel"), int(m.group("line")))
                if source is not None:
                    number = m.group("line")
                    block.append(f" {number:>4} | {source}")
                    block.append(f" {' ' * max(len(number), 4)} | {' ' * (int(m.group('col')) - 1)}^")
            for extra in lines[k + 1:k + 6]:
                if re.match(r"^(\S+:\d+:\d+: (error|warning)|FAILED:|ninja:|\[\d+/\d+\]|make)", extra):
                    break
                block.append(extra)
            return "\n".join(block)
    tail = [l for l in lines if l.strip()][-8:]
    return "\n".join(tail) if tail else "(the build printed nothing)"


# --------------------------------------------------------------------------
# One submission
# --------------------------------------------------------------------------

def read_submission(ctx: Context, rt_folder: Path, root: Path, outcome: Outcome) -> Dict[str, StudentFile]:
    """The student's copies of the reference's headers that hold regions, and the notes on
    what the grader ignores."""
    reference = ctx.reference
    students: Dict[str, StudentFile] = {}
    notes: List[str] = []
    handed_in = sorted(p.relative_to(rt_folder).as_posix() for p in rt_folder.rglob("*")
                       if p.is_file() and p.name.endswith(HEADER_SUFFIXES))
    # a header at its kit path first, then one taken by its file name (handed in loose)
    exact = {f"include/rt/{name}" for name in handed_in}
    kit_files = set(reference.plan.files)
    taken: Dict[str, str] = {}
    for name in sorted(handed_in, key=lambda n: f"include/rt/{n}" not in kit_files):
        rel = reference_path(name, reference.plan.files) or f"include/rt/{name}"
        if rel != f"include/rt/{name}":
            if rel in exact or rel in taken:
                notes.append(f"{name}: the kit's {rel} was handed in too; this copy is ignored")
                continue
            notes.append(f"{name}: graded as {rel}, the kit's header of that name")
        taken[rel] = name
        try:
            # the exact bytes: a byte that is not UTF-8 stays one (a surrogate), for the region
            # scanner to refuse, rather than becoming U+FFFD, which the compiler never sees
            text = (rt_folder / name).read_bytes().decode("utf-8", errors="surrogateescape")
        except OSError:
            continue
        if rel in reference.by_file:
            student = read_student_file(rel, text)
            students[rel] = student
            notes += student.notes
            known = {(r.stage, r.title) for r in reference.by_file[rel]}
            for key, region in sorted(student.regions.items(), key=lambda kv: kv[1].begin_line):
                if key not in known:
                    notes.append(f"{rel}:{region.begin_line}: expected a region the kit has, found "
                                 f"stage{key[0]:02d}: {key[1]}; keep the marker lines as they are "
                                 f"(this region is ignored)")
            differs = outside_differences(student, reference.text(rel), reference.by_file[rel])
            if differs is not None:
                notes.append(f"{rel}:{differs}: expected the kit's lines outside the exercise regions, found "
                             f"other lines; only the regions are graded, so they are ignored")
        elif rel in reference.plan.files:
            if " ".join(normalise(text).split()) != " ".join(normalise(reference.text(rel)).split()):
                notes.append(f"{rel}: expected the kit's header, found another; it holds no exercise "
                             f"region, so the kit's is used")
        else:
            notes.append(f"{rel}: a header the kit does not have; it is ignored (helpers belong inside "
                         f"the exercise regions)")
    where = rt_folder.relative_to(root).as_posix() if rt_folder != root else "."
    outcome.notes.append(f"Graded the exercise regions of {len(students)} headers from {where}/ of the "
                         f"submission: only the lines between the RT_EXERCISE markers are taken from it.")
    if len(notes) > MAX_NOTES:
        notes = notes[:MAX_NOTES] + [f"... and {len(notes) - MAX_NOTES} more"]
    outcome.notes += notes
    return students


def grade_one(ctx: Context, submission: Path, work: Path, slot: Slot, build_jobs: int, case_jobs: int) -> Outcome:
    started = time.monotonic()
    deadline = Deadline(ctx.budget)
    suites = make_suites(ctx)
    outcome = Outcome(suites)
    reference, cache = ctx.reference, ctx.cache
    sub = work / "submission"
    shutil.rmtree(sub, ignore_errors=True)
    try:
        unpack(submission, sub)
        rt_folder = find_rt_folder(sub, [Path(f).name for f in reference.include_files])
    except SubmissionError as e:
        for s in suites:
            s.build_error = f"not graded: {e}"
        outcome.notes.append(str(e))
        outcome.status = f"not graded: {e}"
        outcome.seconds = time.monotonic() - started
        return outcome
    students = read_submission(ctx, rt_folder, sub, outcome)

    # which of the student's regions each graded stage takes
    accepted: Dict[Tuple[str, int], object] = {}      # (file, reference BEGIN line) -> StudentRegion
    refused: Dict[int, List[str]] = {}
    missing: Dict[int, List[str]] = {}
    for r in reference.regions:
        mine = students.get(r.path)
        region = mine.regions.get((r.stage, r.title)) if mine else None
        if region is None:
            missing.setdefault(r.stage, []).append(f"{r.function} ({r.path})")
        elif region.problem:
            refused.setdefault(r.stage, []).append(region.problem)
        else:
            accepted[(r.path, r.begin_line)] = region
    for s in suites:
        if s.stage in refused:
            s.refused = "\n".join(refused[s.stage])
        if s.stage in missing:
            s.remarks.append("Not handed in (graded as not done): " + ", ".join(missing[s.stage]) + ".")

    by_name = {t.name: t for t in cache.targets(set(ctx.stages))}

    # each stage's server: the student's code of the stage, built as the slot's test user
    user = slot_user(ctx.user, slot.index, ctx.uid_block)
    uid, gid = (user.uid, user.gid) if user.dedicated else (None, None)
    slot.prepare(uid, gid)
    maps = LineMaps(student_lines={rel: f.lines for rel, f in students.items()})
    to_build = [stage for stage in ctx.stages if stage not in refused]
    strip = [str(cache.tree), str(cache.root), str(work)]
    suite_of = {(s.stage, s.hidden): s for s in suites}
    if to_build:
        ensure_judges(ctx, to_build)
        log(f"grade: building the servers of stages {', '.join(f'{s:02d}' for s in to_build)}")

    def body_of(r) -> object:
        mine = accepted.get((r.path, r.begin_line))
        return mine if mine is not None else "stub"

    def compile_server(name: str, files, table: str, limit: float) -> Tuple[Optional[Path], str]:
        """(the server program, "") or (None, why it is not built)."""
        root = slot.write_server(name, files, table, uid, gid)
        maps.roots[str(root)] = files
        limit = min(limit, deadline.left())
        if limit <= 0:
            return None, f"not built: the time budget of {ctx.budget:.0f} s ran out"
        code, out = run(user.command(cache.server_command(root, root / "server")), cwd=root, timeout=limit,
                        env=user.environment(root, uuid.uuid4().hex),
                        preexec=user.limits(max(ctx.memory_mb * 2, 2048), cpu_seconds=int(limit) + 1))
        if code == -1:
            if deadline.expired():
                return None, f"not built: the time budget of {ctx.budget:.0f} s ran out"
            return None, (f"not built: the stage's compile time limit of {ctx.weights.compile_timeout:.0f} s ran "
                          f"out (compile_timeout_seconds); look for a template or constexpr computation that "
                          f"never ends")
        if code != 0:
            return None, first_compiler_error(out, strip, maps)
        return root / "server", ""

    def build_stage(stage: int) -> Tuple[int, Optional[Path], str]:
        files = judge.server_overlay(reference, stage, body_of, students, ctx.cumulative)
        program, error = compile_server(f"stage{stage:02d}", files, judge.server_table(reference, stage),
                                        ctx.weights.compile_timeout)
        return stage, program, error

    def build_group(item: Tuple[int, List[int]]) -> List[Tuple[int, Optional[Path], str]]:
        """One server for several stages (judge.group_overlay): the headers are parsed once.
        When it does not build (or not soon: a correct group takes seconds), each of its
        stages is built alone, so that a mistake or a bomb costs its own stage only and the
        message is that stage's."""
        index, group = item
        if len(group) > 1:
            files = judge.group_overlay(reference, group, body_of, students, ctx.cumulative)
            program, error = compile_server(f"group{index}", files, judge.group_table(reference, group),
                                            min(ctx.weights.compile_timeout, GROUP_COMPILE_SECONDS))
            if program is not None:
                return [(stage, program, "") for stage in group]
            if error.startswith("not built: the time budget"):
                return [(stage, None, error) for stage in group]
        return [build_stage(stage) for stage in group]

    # the cases of each suite, the longest (at calibration) first
    work_of: Dict[int, List[Tuple[float, Suite, Path, int, Case]]] = {}
    for s in suites:
        if s.refused or s.stage not in to_build:
            continue
        cases: List[Case] = []
        items = []
        for name in s.targets:
            t = by_name[name]
            known = cache.cases(t)
            if known is None:
                s.note = f"not run: {name}: its judge was not calibrated"
                break
            for entry in known:
                case = Case(str(entry[0]))
                cases.append(case)
                seconds = float(entry[3]) if len(entry) > 3 else 0.0
                items.append((seconds, s, cache.judge_program(t), int(entry[1]), case))
        if s.note:
            continue
        if not cases:
            s.note = "no test case was found"
            continue
        s.cases = cases
        work_of.setdefault(s.stage, []).extend(items)

    stage_deadlines: Dict[int, float] = {}
    lock = threading.Lock()
    run_dir = slot.path
    servers: Dict[int, Path] = {}

    def one(item: Tuple[float, Suite, Path, int, Case]) -> None:
        """One case in its judge, its stage's server answering the judge's calls."""
        _, s, program, expected, case = item
        with lock:     # a suite's time starts with its first case
            stage_deadline = stage_deadlines.setdefault(id(s), time.monotonic() + ctx.weights.stage_timeout)
        left = min(stage_deadline - time.monotonic(), deadline.left())
        if deadline.left() <= 0:
            case.output = f"not run: the time budget of {ctx.budget:.0f} s ran out"
            return
        if left <= 0:
            case.output = (f"not run: the stage's time limit of {ctx.weights.stage_timeout:.0f} s was "
                           f"used up by the cases before it")
            return
        with ctx.processors.one() as cpu:
            case.status, output, case.seconds, _ = run_judged(
                program, case.name, servers[s.stage], run_dir, min(ctx.weights.case_timeout, left), ctx.memory_mb,
                user, expected, s.stage, cpu)
        output = maps.rewrite(output)
        for prefix in strip:
            output = output.replace(prefix.rstrip("/") + "/", "")
        case.output = clip(output)

    # builds and cases in one pool: a group's cases start as soon as its server is built,
    # while the other groups still build
    jobs = max(1, min(build_jobs, len(to_build)))
    groups = [g for g in (to_build[k * len(to_build) // jobs:(k + 1) * len(to_build) // jobs]
                          for k in range(jobs)) if g]
    pending: List[concurrent.futures.Future] = []
    pool = concurrent.futures.ThreadPoolExecutor(max(1, jobs, case_jobs))

    def build_and_queue(item: Tuple[int, List[int]]) -> None:
        results = build_group(item)
        ready = []
        with lock:
            for stage, program, error in results:
                for hidden in (False, True):
                    s = suite_of.get((stage, hidden))
                    if s is None:
                        continue
                    if error.startswith("not built: the time budget"):
                        s.note = "not run: " + error[len("not built: "):] + " while building"
                    elif error:
                        s.build_error = error
                    if error:
                        s.cases = []
                if program is not None:
                    servers[stage] = program
                    ready += work_of.get(stage, [])
                    log(f"grade: running stage{stage:02d}: {len(work_of.get(stage, []))} cases")
            ready.sort(key=lambda w: -w[0])
            pending.extend(pool.submit(one, w) for w in ready)

    try:
        with lock:
            pending.extend(pool.submit(build_and_queue, g) for g in enumerate(groups))
        done = 0
        while True:
            with lock:
                if done == len(pending):
                    break
                future = pending[done]
            future.result()
            done += 1
    finally:
        pool.shutdown(wait=True)
    if to_build:
        reap_all(user)
    not_run = sum(s.not_run for s in suites)
    skipped = [s.label for s in suites if s.note.startswith("not run")]
    parts = ([f"{not_run} cases not run"] if not_run else []) + (["suites not run: " + ", ".join(skipped)]
                                                                  if skipped else [])
    if parts:
        outcome.status = "graded; " + "; ".join(parts)
    outcome.seconds = time.monotonic() - started
    return outcome


def _read(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except OSError:
        return ""


# --------------------------------------------------------------------------
# Reports
# --------------------------------------------------------------------------

def student_output(ctx: Context, outcome: Outcome) -> str:
    """The top-level output students see: the mode, the visible suites' table, the notes."""
    visible = [s for s in outcome.suites if not s.hidden]
    parts = [ctx.mode_line, table(visible)]
    if any(s.hidden for s in outcome.suites):
        parts.append("The total above is of the visible tests; other tests may count as well.")
    parts += outcome.notes
    if not ctx.user.dedicated:
        parts.append(ctx.user.describe())
    return "\n".join(parts)


def grader_output(ctx: Context, outcome: Outcome) -> str:
    """The grader's own output (stdout, which Gradescope hides): every suite."""
    parts = [ctx.mode_line, table(outcome.suites)] + outcome.notes + ctx.instructor_notes
    parts.append(ctx.user.describe() + f"; graded in {outcome.seconds:.1f} s")
    return "\n".join(parts)


def write_reports(ctx: Context, outcome: Outcome, results_path: Path, junit_path: Path) -> None:
    results = gradescope_results(outcome.suites, ctx.weights.hidden_visibility, student_output(ctx, outcome),
                                 outcome.seconds, ctx.mode_line)
    write_atomically(results_path, (json.dumps(results, indent=2) + "\n").encode("utf-8"))
    write_atomically(junit_path, junit_bytes(outcome.suites))


# --------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------

def make_context(args: argparse.Namespace, work: Path) -> Context:
    reference_root = Path(args.reference).resolve()
    for tool in ("cmake", "ninja"):
        if shutil.which(tool) is None:
            raise GradeError(f"expected {tool} on PATH, found none; install cmake and ninja-build")
    cache_dir = Path(args.cache).resolve() if args.cache else work / "cache"
    reference = Reference(reference_root, exclude=[cache_dir, work])
    weights = load_weights(Path(args.weights) if args.weights else reference_root / "tools" / "weights.json")
    if args.stage_timeout is not None:
        weights.stage_timeout = args.stage_timeout
    if args.case_timeout is not None:
        weights.case_timeout = args.case_timeout
    hidden = None
    if args.hidden:
        hidden = Path(args.hidden).resolve()
        if not hidden.is_dir():
            raise GradeError(f"{hidden}: expected a folder of hidden suites, found none")
    stages = parse_stages(args.stages, sorted(reference.stages))
    user = choose_user(args.run_as)
    # the test user compiles and runs the submissions: it must read neither the reference's
    # bodies nor the hidden suites
    secret = [reference.root / rel for rel in sorted(reference.by_file) if rel.startswith("include/")][:1]
    if hidden is not None:
        secret += [hidden] + sorted(p for p in hidden.rglob("*.cpp"))[:1]
    readable = user.first_readable(secret, user.environment(Path("/"), uuid.uuid4().hex))
    if readable is not None:
        top = hidden if hidden is not None and (readable == hidden or hidden in readable.parents) else reference.root
        raise GradeError(f"{readable}: expected a file the test user {user.name} cannot read (it compiles and runs "
                         f"the submissions, and this holds the reference's code or the hidden tests), found it "
                         f"readable; run `chmod -R go-rwx {top}`, or grade from a copy only you can read")
    cache = Cache(cache_dir, reference, hidden)
    cache.prepare()
    names.keep_in(cache.root / "names")
    ctx = Context(reference, weights, stages, cache, user, args.cumulative, args.budget, args.memory_mb)
    if user.dedicated:
        ctx.uid_block = claim_uid_block()
    for stage in sorted(set(weights.stages) - set(reference.stages)):
        ctx.instructor_notes.append(f"stage {stage:02d} is in the weights file but has no tests: not graded")
    return ctx


def calibrate(ctx: Context, jobs: int, timeout: float, stages: Optional[Sequence[int]] = None) -> str:
    """Builds the judges of the chosen stages and the reference's servers, lists each
    judge's cases and runs each with the reference's server, to record the assertions a
    correct answer makes (a case passes only with as many)."""
    started = time.monotonic()
    stages = list(stages if stages is not None else ctx.stages)
    cache, reference = ctx.cache, ctx.reference
    log(f"grade: building the judges of stages {', '.join(f'{s:02d}' for s in stages)}")
    cache.build_judges(set(stages), jobs, timeout)
    grader = TestUser("grader", os.getuid(), os.getgid())   # the reference's code is trusted

    def build_reference(stage: int) -> str:
        files = judge.server_overlay(reference, stage, lambda r: "reference", {})
        root = cache.reference_server(stage).parent
        shutil.rmtree(root, ignore_errors=True)
        for rel in reference.include_files:
            destination = root / rel
            destination.parent.mkdir(parents=True, exist_ok=True)
            if rel in files:
                destination.write_text(files[rel].text, encoding="utf-8")
            else:
                shutil.copyfile(reference.root / rel, destination)
        (root / "judge_table.hpp").write_text(judge.server_table(reference, stage), encoding="utf-8")
        code, out = run(cache.server_command(root, root / "server"), cwd=root, timeout=timeout)
        return "" if code == 0 else first_compiler_error(out, [str(cache.root)])

    with concurrent.futures.ThreadPoolExecutor(max(1, jobs)) as pool:
        errors = dict(zip(stages, pool.map(build_reference, stages)))
    broken = {s: e for s, e in errors.items() if e}
    if broken:
        stage, error = sorted(broken.items())[0]
        raise GradeError(f"the reference's server of stage {stage:02d} does not build (a static C++ build: "
                         f"libc6-dev and libstdc++ are needed):\n{error}")
    found: Dict[str, List[List[object]]] = {}
    runs: List[Tuple[str, Path, Path, str]] = []
    for t in cache.targets(set(stages)):
        program = cache.judge_program(t)
        code, out = run([str(program), "--list-test-cases", "--no-version"], cwd=cache.root, timeout=60)
        names = [l for l in out.splitlines() if l.strip() and not l.startswith("[doctest]") and not l.startswith("=====")]
        source = _read(t.source)
        if code != 0:
            raise GradeError(f"{t.name}: its cases could not be listed:\n{out[-2000:]}")
        if "TEST_CASE_TEMPLATE" not in source:
            expected = len(re.findall(r"^\s*(?:TEST_CASE|TEST_CASE_FIXTURE|SCENARIO)\s*\(", source, re.MULTILINE))
            if len(names) != expected or len(set(names)) != len(names):
                raise GradeError(f"{t.name}: expected {expected} distinct cases, as in its source, found "
                                 f"{len(names)} listed by its judge")
        found[t.name] = [[n, 0, False, 0.0] for n in names]
        runs += [(t.name, program, cache.reference_server(t.stage), n) for n in names]

    def run_one(item: Tuple[str, Path, Path, str]) -> Tuple[str, str, int, bool, str, float]:
        name, program, server, case = item
        with ctx.processors.one() as cpu:
            status, output, seconds, verdict = run_judged(program, case, server, cache.root,
                                                          ctx.weights.case_timeout, ctx.memory_mb, grader, 0, cpu)
        return name, case, verdict.assertions if verdict else 0, status == "passed", output, seconds

    failing = []
    with concurrent.futures.ThreadPoolExecutor(max(1, jobs)) as pool:
        for name, case, assertions, passed, output, seconds in pool.map(run_one, runs):
            for entry in found[name]:
                if entry[0] == case:
                    entry[1:] = [assertions, passed, round(seconds, 3)]
            if not passed:
                failing.append(f"{name}: {case}")
    cache.record_cases(found)
    note = ""
    if failing:
        note = (f"; {len(failing)} cases fail with the reference's own code and can be passed by no submission: "
                + "; ".join(failing[:5]))
        log("grade: " + note[2:])
    return (f"grade: calibrated {cache.root}: the judges of {len(found)} suites of stages "
            f"{', '.join(f'{s:02d}' for s in stages)}, {len(runs)} cases run with the reference, in "
            f"{time.monotonic() - started:.1f} s{note}")


def ensure_judges(ctx: Context, stages: Sequence[int]) -> None:
    """Calibrates the stages whose judges are not (the first grading with a new cache).
    One calibration at a time, whoever asks: the workers of a batch, or two graders with
    one cache, would otherwise build the reference's servers in the same folders."""
    if all(ctx.cache.cases(t) is not None for t in ctx.cache.targets(set(stages))):
        return
    with _flock(ctx.cache.root / ".calibrate.lock"):
        ctx.cache.forget_cases()
        missing = sorted({t.stage for t in ctx.cache.targets(set(stages)) if ctx.cache.cases(t) is None})
        if missing:
            log(f"grade: the judges of stages {', '.join(f'{s:02d}' for s in missing)} are not calibrated: "
                f"calibrating them now (--calibrate does it once, ahead)")
            log(calibrate(ctx, os.cpu_count() or 2, max(ctx.budget, 600), missing))


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description="Grade a student's rt stage by stage.")
    parser.add_argument("submission", nargs="?", help="a folder or a .zip/.tar.gz/.tgz/.tar of include/rt or the repository")
    parser.add_argument("--batch", metavar="FOLDER",
                        help="grade every submission in FOLDER (subfolders or archives; the student is the "
                             "entry's name) into OUT/<student>/ and write OUT/grades.csv")
    parser.add_argument("--reference", default=str(make_kit.DEFAULT_SOURCE),
                        help="the reference repository (default: the one holding this script)")
    parser.add_argument("--hidden", help="folder of hidden suites stageNN_<name>.cpp (and data/)")
    parser.add_argument("--weights", help="weights file (default: <reference>/tools/weights.json)")
    parser.add_argument("--stages", help="grade only these stages, e.g. 3 or 3,4 or 3-5 (default: every stage)")
    parser.add_argument("--cumulative", action="store_true",
                        help="build every suite with the student's code of every stage (default: each stage "
                             "judged alone, with the reference's code of the other stages)")
    parser.add_argument("--out", default="grade-results", help="folder for results.json and junit.xml")
    parser.add_argument("--results-json", help="where to write the Gradescope results (default: OUT/results.json)")
    parser.add_argument("--junit", help="where to write the JUnit XML (default: OUT/junit.xml)")
    parser.add_argument("--cache", help="the prepared build trees (made when missing; default: a temporary one)")
    parser.add_argument("--calibrate", action="store_true",
                        help="prepare --cache DIR (build the chosen stages' suites) and exit")
    parser.add_argument("--work", help="working folder (default: a temporary folder, removed afterwards)")
    parser.add_argument("--budget", type=float, default=DEFAULT_BUDGET,
                        help=f"seconds a submission may take in all, builds and cases (default {DEFAULT_BUDGET})")
    parser.add_argument("--stage-timeout", type=float, help="seconds for all of one suite's cases (overrides weights)")
    parser.add_argument("--case-timeout", type=float, help="seconds for one case (overrides weights)")
    parser.add_argument("--memory-mb", type=int, default=4096, help="address-space limit per test case (0: none)")
    parser.add_argument("--jobs", type=int, default=2,
                        help="processes at once: compilers and cases of one submission, or submissions in --batch")
    parser.add_argument("--run-as", metavar="USER",
                        help="the user that runs the tests when the grader is root (default: rtgrader)")
    args = parser.parse_args(argv)
    if args.calibrate and not args.cache:
        parser.error("--calibrate needs --cache DIR")
    if not args.calibrate and not args.batch and not args.submission:
        parser.error("give the submission (a folder or an archive), --batch FOLDER or --calibrate")
    if args.batch and args.submission:
        parser.error("give either a submission or --batch FOLDER")
    if args.jobs < 1:
        parser.error("--jobs: expected 1 or more")

    temporary = None
    if args.work:
        work = Path(args.work).resolve()
        work.mkdir(parents=True, exist_ok=True)
    else:
        temporary = tempfile.mkdtemp(prefix="rt-grade-")
        work = Path(temporary)
    os.chmod(work, 0o711)
    try:
        ctx = make_context(args, work)
        if args.calibrate:
            print(calibrate(ctx, args.jobs, max(args.budget, 600)))
            return 0
        if args.batch:
            return grade_batch(ctx, Path(args.batch), Path(args.out), work, args.jobs, grade_one, write_reports)
        out = Path(args.out)
        results_path = Path(args.results_json) if args.results_json else out / "results.json"
        junit_path = Path(args.junit) if args.junit else out / "junit.xml"
        with ctx.cache.slot(args.jobs, max(args.budget, 600)) as slot:
            place = work / "current"
            shutil.rmtree(place, ignore_errors=True)
            place.mkdir(parents=True)
            outcome = grade_one(ctx, Path(args.submission), place, slot, args.jobs, args.jobs)
        write_reports(ctx, outcome, results_path, junit_path)
        print(grader_output(ctx, outcome), flush=True)
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
