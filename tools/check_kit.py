#!/usr/bin/env python3
"""check_kit.py - proves the student kit works, for CI.

    python3 tools/check_kit.py                 # everything below
    python3 tools/check_kit.py --no-reference  # when CI has built and tested the reference already
    python3 tools/check_kit.py --no-reference --only 7,9   # two per-stage kits, while working on them
    python3 tools/check_kit.py --leaks                     # the leak check alone (every kit, in memory)
    python3 tools/check_kit.py --leaks ../rt-week3         # the leak check of kits written to folders
    python3 tools/check_kit.py --no-reference --mistakes   # CI: then every page's mistakes, planted
    python3 tools/check_kit.py --mistakes-only --only 4    # stage 04's planted mistakes alone

1. The markers are valid (tools/make_kit.py --check).
1b. No kit make_kit writes (--from-stage N, for every stage N) holds an exercise's answer
   outside the exercise's own region: for every region of the reference, no text file of
   the kit holds LEAK_RUN of its distinctive lines in a row (leak_key: comments,
   whitespace and `rt::` ignored; a line counts when it holds LEAK_WORDS names or numbers,
   so braces, `else` and `return false;` never do). Each leak is one line
   "file:line: holds N lines of the answer to stageNN: title (from include/rt/x.hpp:line)".
2. The reference builds with -Werror and passes every test (hidden suites included; the tools'
   own tests, label tools, are left to CI's ordinary ctest run).
3. A kit with every stage stripped builds with -Werror (test suites, stage programs and the
   header check; also with clang++ and libc++, the standard library of macOS, when they are
   installed: its library and stage suites are judged by the same rule), and then
   - a case of a stripped stage either passes (it tests unmarked code) or fails with the
     not-done message of one of its own stage's exercises; every stripped stage has at
     least one such failure (so its tests can fail);
   - every stage program exits with 3 and "not done yet: ..." on scenes/showcase.scene
     (stage 10's on scenes/soft.scene, the first scene that reaches its exercises).
4. For each stage with exercise regions, a kit with only that stage stripped: its cases fail
   as above, every case of every other stage passes; its own stage program exits 3 naming
   the stage and every earlier stage's program exits 0 (a program runs the student's code of
   its stage and earlier ones, nothing later). These kits are one build, the switchable kit
   (make_kit.switchable_plan: every region solved, and RT_KIT_STRIP=N makes those a kit
   stripping stage N strips throw its not-done message), run once per stage: a test run and
   the stage's own program instead of a build of each kit (100-180 s more). The test run
   holds only the tests that reach one of the stage's exercises: a first run with nothing
   stripped records them (RT_KIT_TRACE, Trace); the others run the same code whatever
   RT_KIT_STRIP says and keep that run's results.
   That earlier programs exit 0 is checked once for all stages: each program with every
   later stage stripped at once (check_programs_stop). --real-kits builds each kit instead.
   (make_kit writes no such kit: it strips a stage with every later one. A kit stripping
   one stage is the proof that each stage's tests fail alone.)
4b. The switchable kit with nothing stripped (every region filled back from the reference)
   passes its whole ctest: every label, not only the stage suites (solved_report).
5. With --mistakes: every mistake a stage page lists under "Common mistakes" (each table row,
   each bold list item; tools/planted_mistakes.py holds one edit per row, and its coverage
   check fails on a row without one) is planted into the switchable kit, one at a time; only
   the suites of the stage that shows it are rebuilt (ccache makes a repeat nearly free), and
   the case the row names must fail first, with words that name the mistake. One line each:
   "check_kit: planted stage NN: <row>: ok (<case>)".
A failing case of stage k that names another stage's exercise is a bug in that test (it
calls another stage's exercise) and is reported by name. A library case (tests/library_*,
never graded) passes, or fails only with the not-done message of a stage the kit strips: the
library may run the student's code, as the programs do (save_image encodes with it). (ctest
counts such a case as skipped: tests/CMakeLists.txt, so the library label passes in a kit.)

The kits are written into one folder (<work>/kit) that is updated in place, so its build
folder recompiles only what a kit changes; ccache is used when it is installed.
The last line reads "check_kit: N passed, M failed" (one check per kit) and the exit code is
0 only when nothing failed. Python 3 standard library only.
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Set, Tuple

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_kit  # noqa: E402  (the sibling module)
import planted_mistakes  # noqa: E402  (the sibling module)

NOT_DONE_RE = re.compile(r'stage (?P<stage>[0-9]{2}): (?P<title>[^\n"]+?): see (?P<page>[^\s"\']+)')


def log(message: str) -> None:
    print(message, flush=True)


@dataclass
class CaseResult:
    name: str
    stage: int
    passed: bool
    output: str


@dataclass
class KitReport:
    name: str
    problems: List[str] = field(default_factory=list)
    notes: List[str] = field(default_factory=list)
    cases: int = 0
    passed: int = 0
    not_done: int = 0
    library_not_done: int = 0
    seconds: float = 0.0
    messages_seen: Set[str] = field(default_factory=set)


class Builder:
    """One CMake build folder, configured once, built target by target."""

    def __init__(self, source: Path, build: Path, jobs: int, compiler: Optional[str], werror: bool = True):
        self.source, self.build, self.jobs = source, build, jobs
        self.compiler, self.werror = compiler, werror
        self.configured = False
        self.extra: List[str] = []  # more -D options (set, then configured = False, to reconfigure)

    def configure(self) -> Tuple[bool, str]:
        if self.configured:
            return True, ""
        args = ["cmake", "-S", str(self.source), "-B", str(self.build),
                "-DCMAKE_BUILD_TYPE=Debug", f"-DRT_WERROR={'ON' if self.werror else 'OFF'}"]
        if shutil.which("ninja"):
            args += ["-G", "Ninja"]
        if self.compiler:
            args.append(f"-DCMAKE_CXX_COMPILER={self.compiler}")
        if shutil.which("ccache"):
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        args += self.extra
        ok, out = run(args)
        self.configured = ok
        return ok, out

    def targets(self, names: Sequence[str]) -> Tuple[bool, str]:
        ok, out = self.configure()
        if not ok:
            return False, out
        return run(["cmake", "--build", str(self.build), "-j", str(self.jobs), "--target", *names])


def run(args: Sequence[str], cwd: Optional[Path] = None, timeout: Optional[float] = None,
        env: Optional[Dict[str, str]] = None) -> Tuple[bool, str]:
    try:
        p = subprocess.run(list(args), cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout, env=env)
        return p.returncode == 0, p.stdout.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as e:
        return False, (e.stdout or b"").decode("utf-8", "replace") + f"\n(timed out after {timeout} s)"


@functools.lru_cache(maxsize=None)
def has_libcxx() -> bool:
    """clang++ can compile and link against libc++ here (Debian: libc++-dev, libc++abi-dev)."""
    with tempfile.TemporaryDirectory() as folder:
        source = Path(folder) / "probe.cpp"
        source.write_text("#include <string>\nint main() { return int(std::string(\"a\").size()) - 1; }\n")
        ok, _ = run(["clang++", "-stdlib=libc++", str(source), "-o", str(Path(folder) / "probe")])
        return ok


def first_error(output: str) -> str:
    for line in output.splitlines():
        if re.search(r"\b(error|Error)\b", line):
            return line.strip()
    lines = [l for l in output.splitlines() if l.strip()]
    return lines[-1] if lines else "(no output)"


def test_targets(root: Path, hidden: bool = False) -> List[str]:
    names = [f"test_{Path(f).stem}" for files in make_kit.known_stages(root).values() for f in files]
    if hidden and (root / "tests" / "hidden").is_dir():
        names += [f"test_hidden_{p.stem}" for p in sorted((root / "tests" / "hidden").glob("stage[0-9][0-9]_*.cpp"))]
    return names


def program_targets(root: Path) -> List[Tuple[str, Path]]:
    out = []
    stages = root / "stages"
    if stages.is_dir():
        for d in sorted(stages.iterdir()):
            if re.match(r"^[0-9]{2}_", d.name) and (d / "main.cpp").is_file():
                out.append((f"stage{d.name}", d))
    return out


def run_ctest(build: Path, jobs: int, timeout: int, junit: Path,
              env: Optional[Dict[str, str]] = None, numbers: Optional[Sequence[int]] = None,
              labels: Optional[str] = None) -> Tuple[List[CaseResult], str]:
    """Runs every test but the tools' own (label tools: CI's ordinary ctest run has them),
    or of those only the ones numbered `numbers` (ctest -N's numbers), or only those
    whose label matches the regular expression `labels`."""
    if junit.exists():
        junit.unlink()
    chosen = ["-I", "0,0,0," + ",".join(str(n) for n in numbers)] if numbers else []
    if labels:
        chosen += ["-L", labels]
    _, out = run(["ctest", "--test-dir", str(build), "-j", str(jobs), "--timeout", str(timeout),
                  "-LE", "^tools$", "--output-junit", str(junit), "--no-tests=error", *chosen], env=env)
    if not junit.is_file():
        return [], out
    cases = []
    for case in ET.parse(junit).getroot().iter("testcase"):
        name = case.get("name", "")
        m = re.match(r"^stage([0-9]{2})\.", name)
        stage = int(m.group(1)) if m else 0
        status = case.get("status", "")
        system_out = case.find("system-out")
        text = system_out.text if system_out is not None and system_out.text else ""
        cases.append(CaseResult(name, stage, status in ("run", "notrun", "disabled") and
                                case.find("failure") is None, text))
    return cases, out


EMPTY_RUN_RE = re.compile(r"test cases:\s+0\s+\|")


def vacuous(cases: List[CaseResult]) -> List[str]:
    """ctest tests that ran no doctest case, so cannot fail: a ';' in a TEST_CASE name
    makes doctest_discover_tests split it into filters that match nothing."""
    return [f"{c.name}: the ctest test ran no doctest case, so it cannot fail (a ';' in the "
            f"TEST_CASE name splits it in doctest_discover_tests: use another character)"
            for c in cases if c.passed and EMPTY_RUN_RE.search(c.output)]


def judge(report: KitReport, cases: List[CaseResult], stripped: Set[int], region_messages: Dict[str, int]) -> None:
    """Checks the cases of one kit against the rule: exactly the stripped stages fail,
    each with its own not-done message."""
    report.cases = len(cases)
    report.problems.extend(vacuous(cases))
    failures_by_stage: Dict[int, int] = {}
    for case in cases:
        if case.passed:
            report.passed += 1
            continue
        messages = [m.group(0) for m in NOT_DONE_RE.finditer(case.output)]
        named_stages = {int(NOT_DONE_RE.match(m).group("stage")) for m in messages}
        if case.stage == 0:
            # A library case (never graded) may run the student's code through the library,
            # as the programs do (save_image encodes with the student's quantize and tone
            # maps): it may fail only with the not-done message of a stage this kit strips.
            if named_stages and named_stages <= stripped:
                report.library_not_done += 1
            else:
                report.problems.append(f"{case.name}: failed: {first_line(case.output)}")
        elif case.stage not in stripped:
            if named_stages:
                report.problems.append(
                    f"{case.name}: stage {case.stage:02d} is solved in this kit but the case fails with "
                    f"'{messages[0]}': the test calls stage {min(named_stages):02d}'s exercise "
                    f"(a bug in the test: build its inputs directly)")
            else:
                report.problems.append(f"{case.name}: stage {case.stage:02d} is solved in this kit but the "
                                       f"case fails: {first_line(case.output)}")
        elif not messages:
            report.problems.append(f"{case.name}: expected the not-done message of a stage {case.stage:02d} "
                                   f"exercise, found another failure: {first_line(case.output)}")
        elif named_stages != {case.stage}:
            other = min(s for s in named_stages if s != case.stage)
            report.problems.append(f"{case.name}: fails with '{messages[0]}': a stage {case.stage:02d} test "
                                   f"calls stage {other:02d}'s exercise (a bug in the test: build its "
                                   f"inputs directly)")
        else:
            report.not_done += 1
            failures_by_stage[case.stage] = failures_by_stage.get(case.stage, 0) + 1
            report.messages_seen.update(messages)
    for stage in sorted(stripped):
        if not failures_by_stage.get(stage):
            report.problems.append(f"stage {stage:02d} is stripped but none of its cases fails with its "
                                   f"not-done message: its tests cannot fail")


def first_line(output: str) -> str:
    for line in output.splitlines():
        if "ERROR" in line or "error" in line or "FATAL" in line or "Exception" in line:
            return line.strip()
    lines = [l.strip() for l in output.splitlines() if l.strip() and not l.startswith("[doctest]")]
    return lines[-1] if lines else "(no output)"


def run_program(exe: Path, scene: Path, timeout: int = 300,
                env: Optional[Dict[str, str]] = None) -> Tuple[Optional[int], str]:
    """Runs a stage program on `scene` in an empty folder: (exit code, stderr), or
    (None, what went wrong) when it did not finish."""
    with tempfile.TemporaryDirectory() as cwd:
        try:
            p = subprocess.run([str(exe), str(scene)], cwd=cwd, capture_output=True, timeout=timeout, env=env)
        except subprocess.TimeoutExpired:
            return None, f"still running after {timeout} s"
    return p.returncode, p.stderr.decode("utf-8", "replace").strip()


# The scene each stage program runs on: showcase.scene, except for a stage whose
# exercises only a scene of its own reaches (stage 10's area lights, lens and gloss).
PROGRAM_SCENES = {10: "soft.scene"}


def program_scene(kit: Path, number: int) -> Path:
    return kit / "scenes" / PROGRAM_SCENES.get(number, "showcase.scene")


def run_stage_program(report: KitReport, kit: Path, build: Path, target: str, number: int,
                      env: Optional[Dict[str, str]] = None) -> Optional[Tuple[int, str]]:
    """Runs stage `number`'s program on its scene: (exit code, stderr), or None after
    reporting that it was not built or did not finish."""
    exe = build / "stages" / target
    if not exe.is_file():
        report.problems.append(f"{target}: not built")
        return None
    code, err = run_program(exe, program_scene(kit, number), env=env)
    if code is None:
        report.problems.append(f"{target}: {err}")
        return None
    return code, err


def check_programs(report: KitReport, kit: Path, build: Path) -> None:
    for target, folder in program_targets(kit):
        ran = run_stage_program(report, kit, build, target, int(folder.name[:2]))
        if ran is None:
            continue
        code, err = ran
        if code == 3 and "not done yet: stage" in err:
            report.notes.append(f"{target}: exit 3: {err.splitlines()[-1]}")
        else:
            report.problems.append(f"{target}: expected exit 3 and 'not done yet: stage ...', found exit "
                                   f"{code}: {err[-300:] or '(no message)'}")


def check_program_rule(report: KitReport, kit: Path, build: Path, stage: int,
                       env: Optional[Dict[str, str]] = None, earlier: bool = True) -> None:
    """A kit with only `stage` stripped: every program runs the student's code of its own
    stage and earlier ones, and nothing later. So the stage's own program exits 3 naming
    the stage, and every earlier stage's program exits 0 (it reaches no stripped code).
    With earlier=False only the stage's own program runs (check_programs_stop: the
    switchable kit checks the earlier ones once for all stages)."""
    before = len(report.problems)
    for target, folder in program_targets(kit):
        number = int(folder.name[:2])
        if number > stage or (number < stage and not earlier):
            continue  # later programs run this stage's code too
        ran = run_stage_program(report, kit, build, target, number, env)
        if ran is None:
            continue
        code, err = ran
        last = err.splitlines()[-1] if err else "(no message)"
        if number == stage:
            if code == 3 and f"not done yet: stage {stage:02d}" in err:
                report.notes.append(f"{target}: exit 3: {last}")
            else:
                report.problems.append(f"{target}: expected exit 3 and 'not done yet: stage {stage:02d}' (its "
                                       f"own stage is stripped), found exit {code}: {last[-300:]}")
        elif code != 0:
            report.problems.append(f"{target}: expected exit 0 with only stage {stage:02d} stripped (a program "
                                   f"runs no later stage's code), found exit {code}: {last[-300:]}")
    if len(report.problems) == before:
        report.notes.append(f"programs of stages before {stage:02d} exit 0, stage {stage:02d}'s exits 3"
                            if earlier else f"stage {stage:02d}'s program exits 3")


def check_programs_stop(report: KitReport, kit: Path, build: Path, stages: Sequence[int]) -> None:
    """The other half of check_program_rule for the switchable kit, once for all stages:
    each program runs with every later stage of `stages` stripped at once and must exit 0.
    A program that reaches no stripped region behaves the same whichever later stages
    are stripped, so this one run stands for the runs with each later stage stripped
    alone (20 program runs instead of 55 for ten stages)."""
    before = len(report.problems)
    for target, folder in program_targets(kit):
        number = int(folder.name[:2])
        later = sorted(s for s in stages if s > number)
        if not later:
            continue
        report.cases += 1
        env = dict(os.environ, RT_KIT_STRIP=",".join(str(s) for s in later))
        ran = run_stage_program(report, kit, build, target, number, env)
        if ran is None:
            continue
        code, err = ran
        if code != 0:
            last = err.splitlines()[-1] if err else "(no message)"
            report.problems.append(f"{target}: expected exit 0 with the later stages "
                                   f"{', '.join(f'{s:02d}' for s in later)} stripped (a program runs no "
                                   f"later stage's code), found exit {code}: {last[-300:]}")
        else:
            report.passed += 1
    if len(report.problems) == before:
        report.notes.append("every program exits 0 with all later stages stripped")


@dataclass
class Trace:
    """Which stages' exercises each ctest test asked about (kit_check_strips), from one
    run of the switchable kit with nothing stripped and RT_KIT_TRACE set (make_kit's
    KIT_CHECK_SWITCH writes one line per process and stage: the stages as a bit mask,
    then the command line of the ctest test the process belongs to)."""
    cases: List[CaseResult]            # the run's results, every region solved
    asked: Dict[str, int]              # test name -> bit mask of the stages it asked about
    number: Dict[str, int]             # test name -> its number (ctest -I)


def read_trace(build: Path, folder: Path, cases: List[CaseResult]) -> Tuple[Optional[Trace], str]:
    """The trace of a run (see Trace), or None and why it cannot be used."""
    ok, listing = run(["ctest", "--test-dir", str(build), "-N", "--show-only=json-v1"])
    try:
        tests = json.loads(listing)["tests"] if ok else []
    except (ValueError, KeyError):
        tests = []
    if not tests:
        return None, "ctest could not list the tests"
    by_command = {tuple(t.get("command", [])): t["name"] for t in tests}
    trace = Trace(cases, {t["name"]: 0 for t in tests}, {t["name"]: k + 1 for k, t in enumerate(tests)})
    for file in sorted(folder.glob("*.trace")):
        for line in file.read_text(encoding="ascii", errors="replace").splitlines():
            mask, _, command = line.partition(" ")
            try:
                argv = tuple(a.decode("utf-8", "replace") for a in bytes.fromhex(command).split(b"\0")[:-1])
                stages = int(mask)
            except ValueError:
                return None, f"{file.name}: unreadable line '{line[:80]}'"
            name = by_command.get(argv)
            if name is None:
                return None, (f"a process asked about an exercise outside every ctest test "
                              f"({' '.join(argv)[:120] or 'no ctest ancestor found'})")
            trace.asked[name] |= stages
    return trace, ""


def traced_run(kit_build: Path, args: argparse.Namespace, work: Path) -> Tuple[Optional[Trace], str]:
    """Runs the switchable kit's tests once with nothing stripped, recording the trace."""
    folder = work / "trace"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    env = {k: v for k, v in os.environ.items() if k != "RT_KIT_STRIP"}
    env["RT_KIT_TRACE"] = str(folder)
    cases, out = run_ctest(kit_build, args.jobs, args.timeout, work / "switchable-traced.xml", env)
    if not cases:
        return None, f"no test ran: {first_error(out)}"
    return read_trace(kit_build, folder, cases)


# The per-stage kits' build: tests and stage programs only (the kit with every
# stage stripped has built the benchmarks, the header check and the viewer).
PER_STAGE_OPTIONS = ["-DRT_BUILD_BENCH=OFF", "-DRT_HEADER_CHECK=OFF", "-DCMAKE_DISABLE_FIND_PACKAGE_SDL2=ON"]


def solved_report(cases: List[CaseResult], seconds: float) -> KitReport:
    """The kit with every exercise solved (each region filled back from the reference)
    passes its whole ctest: every label, the stage suites, the library's, the bad-input
    rows, the programs' and the docs' checks (the tools' own tests, label tools, aside:
    CI's ordinary ctest run has them)."""
    report = KitReport("every exercise solved: the kit's whole ctest passes")
    report.cases = len(cases)
    report.passed = sum(c.passed for c in cases)
    report.seconds = seconds
    report.problems.extend(vacuous(cases))
    for c in cases:
        if not c.passed:
            report.problems.append(f"{c.name}: fails with every exercise solved: {first_line(c.output)}")
    labels = sorted({c.name.split(".")[0] for c in cases})
    report.notes.append(f"{len(cases)} tests of {len(labels)} kinds ({', '.join(labels)})")
    return report


def check_switchable(source: Path, kit: Path, builder: "Builder", per_stage: List[Tuple[str, Set[int]]],
                     args: argparse.Namespace, work: Path, region_messages: Dict[str, int]) -> List[KitReport]:
    """The per-stage kits from one build: the switchable kit (make_kit.switchable_plan)
    has every region solved, and RT_KIT_STRIP=N makes the regions a kit stripping
    stage N would strip throw that kit's not-done message instead. Each stage's
    tests and programs then run as in its own kit, without ten builds of the tree.
    (A kit that strips one stage compiles if the reference and the kit that strips
    every stage do: a region is either its reference body or its stub.)"""
    reports: List[KitReport] = []
    t0 = time.monotonic()
    plan = make_kit.switchable_plan(source)
    make_kit.sync_kit(source, plan, kit)
    builder.extra = PER_STAGE_OPTIONS
    builder.configured = False
    (kit / "build" / "stages" / "viewer" / "viewer").unlink(missing_ok=True)
    ok, out = builder.targets(["all"])
    built = time.monotonic() - t0
    log(f"check_kit: the switchable kit built in {built:.0f} s")
    # One run with nothing stripped records which stages' exercises each test
    # reaches. A test that never asked about stage N runs, under RT_KIT_STRIP=N,
    # exactly as it did (kit_check_strips answered it the same), so each stage
    # reruns only the tests that asked about it, and takes the rest from this run.
    trace: Optional[Trace] = None
    if ok:
        t1 = time.monotonic()
        trace, why = traced_run(kit / "build", args, work)
        if trace is None:
            log(f"check_kit: note: no trace ({why}); every stage reruns every test")
        else:
            log(f"check_kit: the traced run with nothing stripped took {time.monotonic() - t1:.0f} s")
            reports.append(solved_report(trace.cases, time.monotonic() - t1))
            print_report(reports[-1])
    for name, stripped in per_stage:
        report = KitReport(name)
        t1 = time.monotonic()
        if not ok:
            report.problems.append(f"build of the switchable kit failed (-Werror): {first_error(out)}")
        else:
            env = dict(os.environ, RT_KIT_STRIP=",".join(str(s) for s in sorted(stripped)))
            env.pop("RT_KIT_TRACE", None)
            numbers: Optional[List[int]] = None
            kept: List[CaseResult] = []
            if trace is not None:
                mask = sum(1 << s for s in stripped)
                # a test that failed with nothing stripped is run again, whatever it asked
                rerun = {c.name for c in trace.cases if not c.passed}
                rerun |= {n for n, asked in trace.asked.items() if asked & mask}
                numbers = sorted(trace.number[n] for n in rerun if n in trace.number)
                kept = [c for c in trace.cases if c.name not in rerun]
                report.notes.append(f"{len(numbers)} tests reach a stage {min(stripped):02d} exercise and ran "
                                    f"again; {len(kept)} reach none and kept their results with nothing stripped")
            cases: List[CaseResult] = []
            if numbers is None or numbers:  # (no test reaching the stage: judge says its tests cannot fail)
                cases, ctest_out = run_ctest(kit / "build", args.jobs, args.timeout,
                                             work / f"switchable-{min(stripped):02d}.xml", env, numbers)
                if not cases:
                    report.problems.append(f"no test ran: {first_error(ctest_out)}")
            cases = kept + cases
            real = make_kit.plan_kit(source, stripped)  # which regions that kit strips
            judge(report, cases, {r.stage for r in real.stripped}, region_messages)
            check_program_rule(report, kit, kit / "build", next(iter(stripped)), env, earlier=False)
        report.seconds = time.monotonic() - t1
        reports.append(report)
        print_report(report)
    report = KitReport("programs with the later stages stripped")
    t1 = time.monotonic()
    if ok:
        check_programs_stop(report, kit, kit / "build", sorted(set().union(*(s for _, s in per_stage))))
    report.seconds = time.monotonic() - t1
    reports.append(report)
    print_report(report)
    return reports


# --------------------------------------------------------------------------
# Planted mistakes: every mistake a stage page lists, in a kit with every
# exercise solved, fails first in the test that names it
# --------------------------------------------------------------------------

def suite_binaries(kit: Path, build: Path, stage: int) -> List[Tuple[str, Path]]:
    """A stage's test suites (target, binary) in the order ctest runs them."""
    files = sorted(make_kit.known_stages(kit).get(stage, []))
    return [(f"test_{Path(f).stem}", build / "tests" / f"test_{Path(f).stem}") for f in files]


def run_suites(kit: Path, build: Path, stage: int, timeout: int) -> planted_mistakes.FirstFailure:
    """Runs stage `stage`'s suites in ctest's order (doctest's file order within each)
    and returns the first failing case; every region solved (RT_KIT_STRIP unset)."""
    env = {k: v for k, v in os.environ.items() if k not in ("RT_KIT_STRIP", "RT_KIT_TRACE")}
    for target, exe in suite_binaries(kit, build, stage):
        ok, out = run([str(exe), "--no-colors=true"], cwd=exe.parent, timeout=timeout, env=env)
        first = planted_mistakes.first_failure(out)
        if first:
            return planted_mistakes.FirstFailure(first[0], first[1], target)
        if not ok:  # no case named: a crash doctest did not catch, or a timeout
            return planted_mistakes.FirstFailure(f"({target} ended without naming a case)", out[-600:], target)
    return planted_mistakes.FirstFailure()


def check_mistakes(source: Path, kit: Path, builder: "Builder", only: Optional[Set[int]], timeout: int) -> KitReport:
    """Plants each mistake of tools/planted_mistakes.py in `kit` (every region solved),
    one at a time: rebuilds only the suites of the stage that shows it, runs them, and
    checks that the case the mistake names fails first with words naming the mistake.
    The kit's files are put back after each."""
    report = KitReport("planted mistakes: each fails first in the test that names it")
    t0 = time.monotonic()
    report.problems += planted_mistakes.coverage(source)
    mistakes = [m for m in planted_mistakes.MISTAKES if only is None or m.stage in only]
    for mistake in mistakes:
        report.cases += 1
        originals, planted, problems = planted_mistakes.planted_texts(kit, mistake)
        if problems:
            report.problems += problems
            continue
        try:
            for rel, text in planted.items():
                (kit / rel).write_text(text, encoding="utf-8")
            targets = [t for t, _ in suite_binaries(kit, builder.build, mistake.shown_by)]
            ok, out = builder.targets(targets)
            if not ok:
                report.problems.append(f"{mistake.label()}: the planted mistake does not build: {first_error(out)}")
                continue
            found = run_suites(kit, builder.build, mistake.shown_by, timeout)
        finally:
            for rel, text in originals.items():
                (kit / rel).write_text(text, encoding="utf-8")
        problems = planted_mistakes.judge(mistake, found)
        report.problems += problems
        log(f"check_kit: planted {mistake.label()}: "
            + ("ok" if not problems else "FAILED") + f" ({found.case[:60] or 'nothing fails'})")
        if not problems:
            report.passed += 1
            report.notes.append(f"{mistake.label()} -> stage{mistake.shown_by:02d}.{found.case[:70]}: "
                                f"{planted_mistakes.message_excerpt(mistake, found.output)}")
    # the suites as they were, so that nothing after this runs a planted binary
    builder.targets([t for s in sorted({m.shown_by for m in mistakes}) for t, _ in suite_binaries(kit, builder.build, s)])
    report.seconds = time.monotonic() - t0
    return report


# --------------------------------------------------------------------------
# Leaks: no kit holds an exercise's answer outside the exercise's own region
# --------------------------------------------------------------------------

# A kit file leaks a region's answer when it holds LEAK_RUN of the region's
# distinctive lines one after the other (every line of a region that has fewer).
# Lines are compared after leak_key: no comment, no whitespace, no `rt::`, no
# brace opening or closing a block at either end. A line is distinctive when it
# holds at least LEAK_WORDS names or numbers besides LEAK_COMMON_WORDS, so `}`,
# `else`, `return false;` and `(void)x;` never count. Measured on the
# reference: no kit holds more than 2 distinctive lines of a region in a row
# outside it (a tree walk in a stage-04 test shares 2 with build_groups, the
# given fresnel_reflectance 2 with refract), while a test helper that copies an
# exercise's body holds 3 or more even with names changed (a copy of the
# textbook quadratic written from its formula holds 6, one of the book's slab
# test or of Moller-Trumbore 3; tools/tests/test_check_kit.py puts copies into
# a kit and sees them reported).
LEAK_RUN = 3
LEAK_WORDS = 3
LEAK_COMMON_WORDS = frozenset({"return", "else", "break", "continue", "true", "false", "do", "try", "default"})
_LEAK_WORD_RE = re.compile(r"[A-Za-z_]\w*|[0-9][\w.']*")


def _without_line_comment(line: str) -> str:
    """`line` without a // comment (one inside a string or a character literal stays)."""
    start = line.find("//")
    if start < 0:
        return line
    if '"' not in line[:start] and "'" not in line[:start]:
        return line[:start]
    quote, i = "", 0
    while i < len(line):
        c = line[i]
        if quote:
            if c == "\\":
                i += 2
                continue
            if c == quote:
                quote = ""
        elif c in "\"'":
            quote = c
        elif line.startswith("//", i):
            return line[:i]
        i += 1
    return line


@functools.lru_cache(maxsize=None)
def leak_key(line: str) -> Optional[str]:
    """The line as the leak check compares it, or None when it is not distinctive."""
    text = _without_line_comment(line).strip()
    if not text or text.startswith(("#", "/*", "*")):
        return None
    if sum(1 for w in _LEAK_WORD_RE.findall(text) if w not in LEAK_COMMON_WORDS) < LEAK_WORDS:
        return None
    # `if (x) {` and `if (x)`, `} else if (x) {` and `else if (x)`: the same line in another layout
    return "".join(re.sub(r"\brt::", "", text).split()).lstrip("}").rstrip("{")


@dataclass
class Answer:
    """The distinctive lines of one region of the reference: (key, line number)."""
    region: make_kit.Region
    lines: List[Tuple[str, int]]

    @property
    def run(self) -> int:
        """How many of its lines in a row make a leak."""
        return min(LEAK_RUN, len(self.lines))


def reference_answers(root: Path, regions: Sequence[make_kit.Region]) -> List[Answer]:
    answers = []
    for r in regions:
        body = (root / r.path).read_text(encoding="utf-8").split("\n")[r.begin_line:r.end_line - 1]
        keyed = [(leak_key(l), r.begin_line + 1 + k) for k, l in enumerate(body)]
        answers.append(Answer(r, [(key, n) for key, n in keyed if key]))
    return answers


def plan_texts(root: Path, plan: "make_kit.KitPlan") -> List[Tuple[str, str]]:
    """(path, text) of every text file of the kit `plan` describes, without writing it."""
    out = []
    for rel in plan.files:
        if rel in plan.contents:
            out.append((rel, plan.contents[rel]))
            continue
        try:
            out.append((rel, (root / rel).read_text(encoding="utf-8")))
        except (UnicodeDecodeError, OSError):
            pass  # an image, a binary mesh: no C++ to hold an answer
    return out


def folder_texts(kit: Path) -> List[Tuple[str, str]]:
    """(path, text) of every text file of a kit written to `kit` (build folders left out)."""
    out = []
    for dirpath, dirnames, filenames in os.walk(kit):
        dirnames[:] = sorted(d for d in dirnames if d not in make_kit.ALWAYS_SKIPPED_DIRS
                             and not make_kit.BUILD_DIR_RE.match(d))
        for name in sorted(filenames):
            path = Path(dirpath, name)
            try:
                out.append((path.relative_to(kit).as_posix(), path.read_text(encoding="utf-8")))
            except (UnicodeDecodeError, OSError):
                pass
    return out


def _runs(keys: List[Tuple[str, int]], index: Dict[str, List[Tuple[int, int]]]) -> Dict[int, Tuple[int, int, int]]:
    """For each answer, its longest run in `keys` (a kit file's distinctive lines, in
    order): answer -> (length, line in the kit file, position in the answer)."""
    best: Dict[int, Tuple[int, int, int]] = {}
    previous: Dict[Tuple[int, int], int] = {}
    for j, (key, _) in enumerate(keys):
        current: Dict[Tuple[int, int], int] = {}
        for a, i in index.get(key, ()):
            length = previous.get((a, i - 1), 0) + 1
            current[(a, i)] = length
            if length > best.get(a, (0, 0, 0))[0]:
                best[a] = (length, keys[j - length + 1][1], i - length + 1)
        previous = current
    return best


@dataclass
class _Segment:
    """The distinctive lines of one part of a kit file: outside its exercise regions
    (answer None), or the body of one region (answer: the index of its own answer)."""
    keys: List[Tuple[str, int]]
    answer: Optional[int]


def _segments(rel: str, text: str, own: Dict[Tuple[str, int, str], int], stages: Set[int]) -> List[_Segment]:
    lines = text.split("\n")
    regions: List[make_kit.Region] = []
    if rel.endswith(make_kit.SOURCE_SUFFIXES) and "RT_EXERCISE_BEGIN" in text:
        regions = make_kit.scan_file(rel, text, stages, [])
    inside: Set[int] = set()
    for r in regions:
        inside.update(range(r.begin_line, r.end_line + 1))
    keyed = [(leak_key(l), k + 1) for k, l in enumerate(lines)]
    out = [_Segment([(key, n) for key, n in keyed if key and n not in inside], None)]
    for r in regions:
        out.append(_Segment([(key, n) for key, n in keyed[r.begin_line:r.end_line - 1] if key],
                            own.get((r.path, r.stage, r.title))))
    return out


def find_leaks(texts: Sequence[Tuple[str, str]], answers: Sequence[Answer], stages: Set[int],
               cache: Optional[Dict[Tuple[str, str], List[_Segment]]] = None) -> List[str]:
    """One line per kit file that holds a run of a region's answer (Answer.run lines in a
    row) where it does not belong: outside every exercise region, or inside another
    region. A region's own answer in its own place is a stage the kit hands out solved,
    as make_kit reports, and no leak; so are its own lines when they are also part of
    another answer (stage 07's ray color, handed out, holds the part of stage 09's that
    repeats it). `cache` keeps each file's parsing between kits."""
    cache = {} if cache is None else cache
    index: Dict[str, List[Tuple[int, int]]] = {}
    for a, answer in enumerate(answers):
        for i, (key, _) in enumerate(answer.lines):
            index.setdefault(key, []).append((a, i))
    own = {(ans.region.path, ans.region.stage, ans.region.title): a for a, ans in enumerate(answers)}
    problems = []
    for rel, text in texts:
        if (rel, text) not in cache:
            cache[(rel, text)] = _segments(rel, text, own, stages)
        for segment in cache[(rel, text)]:
            keys = segment.keys
            if segment.answer is not None:
                mine = {key for key, _ in answers[segment.answer].lines}
                keys = [(key, n) for key, n in keys if key not in mine]  # its own answer is its own
            for a, (length, line, position) in sorted(_runs(keys, index).items()):
                answer = answers[a]
                if length >= answer.run and a != segment.answer:
                    problems.append(f"{rel}:{line}: holds {length} lines of the answer to "
                                    f"stage{answer.region.stage:02d}: {answer.region.title} "
                                    f"(from {answer.region.path}:{answer.lines[position][1]})")
    return problems


def kit_choices(root: Path) -> List[Tuple[str, Set[int]]]:
    """Every kit make_kit writes: --from-stage N for each stage (--from-stage of the first
    is --all), by name and the stages it strips."""
    stages = sorted(make_kit.known_stages(root))
    return [(f"kit from stage {s:02d}", make_kit.select_stages(stages, s, False)) for s in stages]


def check_leaks(root: Path, kits: Optional[Sequence[Path]] = None) -> KitReport:
    """The leak check of every kit make_kit writes (in memory), or of the kit folders `kits`."""
    report = KitReport("no answer outside its exercise region")
    t0 = time.monotonic()
    regions = make_kit.scan_repository(root)
    answers = reference_answers(root, regions)
    stages = set(make_kit.known_stages(root))
    where: Dict[str, List[str]] = {}
    if kits:
        checked = [(str(kit), folder_texts(kit)) for kit in kits]
    else:
        checked = [(name, plan_texts(root, make_kit.plan_kit(root, stripped, regions)))
                   for name, stripped in kit_choices(root)]
    cache: Dict[Tuple[str, str], List[_Segment]] = {}
    for name, texts in checked:
        report.cases += 1
        found = find_leaks(texts, answers, stages, cache)
        report.passed += 0 if found else 1
        for problem in found:
            where.setdefault(problem, []).append(name)
    for problem, names in where.items():
        report.problems.append(problem + (f" [in {len(names)} kits]" if len(names) > 1 else f" [{names[0]}]"))
    short = [a for a in answers if len(a.lines) < LEAK_RUN]
    report.notes.append(f"{len(answers)} regions, each against every text file of {len(checked)} kits: a leak is "
                        f"{LEAK_RUN} of its distinctive lines in a row (lines of at least {LEAK_WORDS} words, "
                        f"comments and whitespace ignored) outside its region; "
                        f"{len(short)} regions have fewer and leak with all of them"
                        + (f" ({', '.join(f'{a.region.stage:02d}: {a.region.title}' for a in short)})" if short else ""))
    empty = [a for a in answers if not a.lines]
    if empty:
        report.notes.append("regions with no distinctive line, never found: " +
                            ", ".join(f"{a.region.where()}" for a in empty))
    report.seconds = time.monotonic() - t0
    return report


def parse_arguments(argv: Optional[Sequence[str]]) -> Tuple[argparse.ArgumentParser, argparse.Namespace]:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", default=str(make_kit.DEFAULT_SOURCE), help="the reference repository")
    parser.add_argument("--work", help="work folder (default: <source>/build/kit-check)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--no-reference", action="store_true", help="skip building and testing the reference")
    parser.add_argument("--no-clang", action="store_true", help="skip the clang++ build of the stripped kit")
    parser.add_argument("--timeout", type=int, default=300, help="seconds per test case (ctest --timeout)")
    parser.add_argument("--real-kits", action="store_true",
                        help="check each per-stage kit as make_kit writes it (one build per kit) instead of "
                             "the switchable kit (one build, stages stripped at run time)")
    parser.add_argument("--only", metavar="N[,N...]",
                        help="only these per-stage kits, without the kit of every stage stripped (while "
                             "working on a stage; CI checks them all)")
    parser.add_argument("--mistakes", action="store_true",
                        help="after the kits, plant every mistake the stage pages list into the switchable kit "
                             "(every exercise solved), one at a time, and check which case fails first and that "
                             "its message names the mistake (tools/planted_mistakes.py)")
    parser.add_argument("--mistakes-only", action="store_true",
                        help="the planted mistakes alone (with --only: of those stages), on the switchable kit")
    parser.add_argument("--leaks", nargs="*", metavar="KIT",
                        help="run the leak check alone: on every kit make_kit writes (in memory), or on the "
                             "kit folders given")
    return parser, parser.parse_args(argv)


def verdict(reports: Sequence[KitReport], started: float) -> int:
    """The closing lines: the time taken, and how many checks passed; the exit code."""
    failed = sum(1 for r in reports if r.problems)
    log(f"check_kit: took {time.monotonic() - started:.0f} s")
    log(f"check_kit: {len(reports) - failed} passed, {failed} failed")
    return 1 if failed else 0


def check_reference(source: Path, work: Path, args: argparse.Namespace) -> KitReport:
    """The reference builds, and every case of its suites passes and asserts something."""
    report = KitReport("reference")
    t0 = time.monotonic()
    builder = Builder(source, work / "reference-build", args.jobs, None)
    ok, out = builder.targets(["all"])
    if not ok:
        report.problems.append(f"build failed: {first_error(out)}")
    else:
        cases, out = run_ctest(work / "reference-build", args.jobs, args.timeout, work / "reference.xml")
        if not cases:
            report.problems.append(f"no test ran: {first_error(out)}")
        report.cases = len(cases)
        report.passed = sum(c.passed for c in cases)
        report.problems.extend(vacuous(cases))
        for c in cases:
            if not c.passed:
                report.problems.append(f"{c.name}: failed in the reference: {first_line(c.output)}")
    report.seconds = time.monotonic() - t0
    return report


def kit_builders(kit: Path, args: argparse.Namespace) -> Tuple[Builder, Optional[Builder]]:
    """The kit's g++ build, and the clang++ one (None without clang++ or with --no-clang)."""
    builder = Builder(kit, kit / "build", args.jobs, None)
    # A kit is a student build (RT_STUDENT_BUILD: no benchmarks, no per-header
    # checks); the kit with every stage stripped builds them anyway, to prove
    # they compile without the exercises.
    builder.extra = ["-DRT_BUILD_BENCH=ON", "-DRT_HEADER_CHECK=ON"]
    # clang++ with libc++, the standard library of macOS (the libcxx preset's choice,
    # without its sanitizers): the stripped kit builds and its suites judge as g++'s do
    clang = None
    if not args.no_clang and shutil.which("clang++"):
        clang = Builder(kit, kit / "build-libcxx", args.jobs, "clang++")
        clang.extra = ["-DRT_HEADER_CHECK=ON"]
        if has_libcxx():
            clang.extra += ["-DCMAKE_CXX_FLAGS=-stdlib=libc++", "-DRT_TINYOBJLOADER_FROM_HEADER=ON"]
    return builder, clang


def check_clang(report: KitReport, kit: Path, work: Path, clang: Builder, name: str, plan: "make_kit.KitPlan",
                region_messages: Dict[str, int], args: argparse.Namespace) -> None:
    """The stripped kit with clang++: the suites and the header check build with -Werror,
    and its suites judge as g++'s do; into `report`."""
    library = "libc++" if has_libcxx() else "libstdc++ (libc++ is not installed)"
    ok, out = clang.targets(["rt_suites", "rt_header_check"])
    if not ok:
        report.problems.append(f"clang++ with {library}: build failed (-Werror): {first_error(out)}")
        return
    clang_report = KitReport(f"{name}, clang++ with {library}")
    cases, out = run_ctest(kit / "build-libcxx", args.jobs, args.timeout, work / "kit-libcxx.xml",
                           labels="^(stage[0-9][0-9]|library)$")
    if not cases:
        report.problems.append(f"clang++ with {library}: no test ran: {first_error(out)}")
    judge(clang_report, cases, {r.stage for r in plan.stripped}, region_messages)
    report.problems += [f"clang++ with {library}: {p}" for p in clang_report.problems]
    report.notes.append(f"clang++ with {library}, -Werror: the suites and the header check build; "
                        f"{clang_report.passed} of {clang_report.cases} cases pass, "
                        f"{clang_report.not_done} fail with their stage's not-done message")


def check_plan(source: Path, kit: Path, work: Path, builder: Builder, clang: Optional[Builder], name: str,
               stripped: Set[int], region_messages: Dict[str, int], args: argparse.Namespace,
               number: int) -> KitReport:
    """One kit as make_kit writes it, synced into `kit`: no instructor-only file, it
    builds with -Werror, and each failing case fails with a stripped stage's message."""
    report = KitReport(name)
    t0 = time.monotonic()
    plan = make_kit.plan_kit(source, stripped)
    make_kit.sync_kit(source, plan, kit)
    leaked = [f for f in plan.left_out if (kit / f).exists()]
    if leaked:
        report.problems.append(f"instructor-only files in the kit: {', '.join(leaked)}")
    first = name == "all stages stripped"
    # every kit builds everything: ctest runs the reliability suites and the stage
    # programs too, and a binary left from the previous kit would test old headers
    ok, out = builder.targets(["all"])
    if not ok:
        report.problems.append(f"build failed (-Werror): {first_error(out)}")
    else:
        cases, out = run_ctest(kit / "build", args.jobs, args.timeout, work / f"kit-{number}.xml")
        if not cases:
            report.problems.append(f"no test ran: {first_error(out)}")
        # a region that repeats a stripped stage's answer is stripped with it (make_kit)
        judge(report, cases, {r.stage for r in plan.stripped}, region_messages)
        if first:
            check_programs(report, kit, kit / "build")
        elif len(stripped) == 1:
            check_program_rule(report, kit, kit / "build", next(iter(stripped)))
    if first:
        # The benchmarks are outside every region: the kit with every stage
        # stripped has just shown that they compile without the exercises.
        # The per-stage kits run tests only, and the benchmarks were about
        # 40% of each kit's compile time (CI runs on 2 cores).
        # The viewer too: it has shown it compiles, no kit check runs it on student
        # code, and most exercise headers reach its one large file (about 40 s a kit).
        # Its old binary goes, so no test runs it with another kit's headers.
        builder.extra = PER_STAGE_OPTIONS
        builder.configured = False
        (kit / "build" / "stages" / "viewer" / "viewer").unlink(missing_ok=True)
    if first and clang is not None:
        check_clang(report, kit, work, clang, name, plan, region_messages, args)
    report.seconds = time.monotonic() - t0
    return report


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser, args = parse_arguments(argv)
    source = Path(args.source).resolve()
    work = Path(args.work).resolve() if args.work else source / "build" / "kit-check"
    started = time.monotonic()
    reports: List[KitReport] = []

    # 1. markers
    try:
        regions = make_kit.scan_repository(source)
    except make_kit.KitError as e:
        for m in e.messages:
            log(m)
        log("check_kit: 0 passed, 1 failed")
        return 1
    stages_with_regions = sorted({r.stage for r in regions})
    all_stages = sorted(make_kit.known_stages(source))
    log(f"check_kit: {len(regions)} regions in stages {', '.join(f'{s:02d}' for s in stages_with_regions)}; "
        f"test suites for stages {', '.join(f'{s:02d}' for s in all_stages)}")

    # 1b. no answer outside its region, in any kit
    if args.leaks:
        missing = [k for k in args.leaks if not Path(k, "include").is_dir()]
        if missing:
            parser.error(f"--leaks: expected kit folders (each holding include/), found {', '.join(missing)}")
    leaks = check_leaks(source, [Path(k) for k in args.leaks] if args.leaks else None)
    reports.append(leaks)
    print_report(leaks)
    if args.leaks is not None:
        failed = 1 if leaks.problems else 0
        log(f"check_kit: {1 - failed} passed, {failed} failed")
        return failed
    work.mkdir(parents=True, exist_ok=True)
    doc_of = {s: make_kit.stage_doc(source, s) for s in all_stages}
    region_messages = {make_kit.not_done_message(r, doc_of.get(r.stage)): r.stage for r in regions}

    if args.mistakes_only:
        chosen_stages = {int(x) for x in args.only.split(",") if x.strip()} if args.only else None
        kit = work / "kit"
        make_kit.sync_kit(source, make_kit.switchable_plan(source), kit)
        builder = Builder(kit, kit / "build", args.jobs, None)
        builder.extra = PER_STAGE_OPTIONS
        report = check_mistakes(source, kit, builder, chosen_stages, args.timeout)
        print_report(report)
        return verdict([report], started)

    # 2. the reference
    if not args.no_reference:
        reports.append(check_reference(source, work, args))
        print_report(reports[-1])

    # 3 and 4. the kits, all in one folder updated in place
    kit = work / "kit"
    builder, clang = kit_builders(kit, args)
    per_stage = [(f"stage {s:02d} stripped", {s}) for s in stages_with_regions]
    plans = [("all stages stripped", set(all_stages))]
    if args.only:
        chosen = {int(x) for x in args.only.split(",") if x.strip()}
        per_stage = [(name, stripped) for name, stripped in per_stage if stripped <= chosen]
        plans = []
        builder.extra = PER_STAGE_OPTIONS
        (kit / "build" / "stages" / "viewer" / "viewer").unlink(missing_ok=True)
        clang = None
    if args.real_kits:
        plans += per_stage
    for name, stripped in plans:
        reports.append(check_plan(source, kit, work, builder, clang, name, stripped, region_messages, args,
                                  len(reports)))
        print_report(reports[-1])

    if not args.real_kits and per_stage:
        reports += check_switchable(source, kit, builder, per_stage, args, work, region_messages)

    if args.mistakes:
        if args.real_kits:  # the switchable kit, every region solved
            make_kit.sync_kit(source, make_kit.switchable_plan(source), kit)
            builder.extra = PER_STAGE_OPTIONS
            builder.configured = False
        chosen_stages = {s for _, stripped in per_stage for s in stripped} if args.only else None
        reports.append(check_mistakes(source, kit, builder, chosen_stages, args.timeout))
        print_report(reports[-1])

    # every exercise reached by at least one failing case (a warning: a case stops at
    # the first exercise it meets, so an exercise may be hidden behind another)
    seen = set().union(*(r.messages_seen for r in reports)) if reports else set()
    for message in ([] if args.only else sorted(set(region_messages) - seen)):
        log(f"check_kit: note: no failing case reported '{message}' first; "
            f"is that exercise tested on its own?")
    return verdict(reports, started)


def print_report(report: KitReport) -> None:
    verdict = "ok" if not report.problems else "FAILED"
    log(f"[{verdict}] {report.name}: {report.cases} cases, {report.passed} passed, "
        f"{report.not_done} failed with their own not-done message, "
        + (f"{report.library_not_done} library cases wait for a stripped stage's exercise, "
           if report.library_not_done else "")
        + f"{report.cases - report.passed - report.not_done - report.library_not_done} other failures "
        f"({report.seconds:.0f} s)")
    for note in report.notes:
        log(f"    {note}")
    for problem in report.problems:
        log(f"    problem: {problem}")


if __name__ == "__main__":
    sys.exit(main())
