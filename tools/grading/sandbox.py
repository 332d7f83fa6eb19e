"""Running a submission's test cases: each in a judge of its own (tools/grading/judge/), with
a time limit, and the student's code in the judge's server: confined, with resource limits,
and, when the grader runs as root, as an unprivileged user that cannot read the grader's
files (the reference and the hidden suites among them).

A case passes only on the judge's verdict (RT_JUDGE_VERDICT_FD, a file the grader opened):
the case passed, none of its assertions failed, it made at least the assertions the
reference's run of it makes, and the judge exited with 0. Nothing the judge prints, and
nothing the student's code does, is read for it.
"""

from __future__ import annotations

import contextlib
import os
import pwd
import re
import shutil
import signal
import stat
import subprocess
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Sequence, Tuple

from .common import GradeError, kill_group, run

DEFAULT_USER = "rtgrader"
RUN_VARIABLE = "RT_GRADE_RUN"
SUMMARY_RE = re.compile(r"\[doctest\] test cases:\s*(\d+)\s*\|\s*(\d+) passed\s*\|\s*(\d+) failed")
MAX_PROCESSES = 512                 # per test user: threads count too
MAX_FILE_BYTES = 256 * 1024 * 1024    # any file a case writes, its output too
OUTPUT_KEPT = 64 * 1024                # of a case's output: its first and its last bytes


@dataclass
class TestUser:
    """Who runs the test cases: a dedicated user (the grader is root) or the grader's own."""
    name: str
    uid: int
    gid: int
    prefix: List[str] = field(default_factory=list)   # the command that switches to the user
    dedicated: bool = False

    def describe(self) -> str:
        if self.dedicated:
            return (f"the tests ran as uids of their own, unprivileged, which cannot read the grader's files "
                    f"(checked as the user {self.name})")
        return (f"the tests ran as {self.name}, the grader's own user (grade.py is not root), so they "
                f"could read every file that user can; run it as root with a test user "
                f"({DEFAULT_USER}) to keep a submission's code from reading the reference")

    def command(self, args: Sequence[str]) -> List[str]:
        return self.prefix + list(args)

    def environment(self, home: Path, token: str) -> Dict[str, str]:
        """The cases' environment; RT_GRADE_RUN=token marks the processes of one submission."""
        env = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": str(home), "TMPDIR": str(home),
               "LANG": "C.UTF-8", "LC_ALL": "C.UTF-8", RUN_VARIABLE: token}
        if not self.dedicated:
            env["PATH"] = os.environ.get("PATH", env["PATH"])
        return env

    def limits(self, memory_mb: int, cpu_seconds: int = 0):
        dedicated = self.dedicated

        def apply() -> None:
            try:
                import resource
                if memory_mb > 0:
                    limit = memory_mb * 1024 * 1024
                    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
                if cpu_seconds > 0:
                    resource.setrlimit(resource.RLIMIT_CPU, (cpu_seconds, cpu_seconds))
                resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
                resource.setrlimit(resource.RLIMIT_FSIZE, (MAX_FILE_BYTES, MAX_FILE_BYTES))
                if dedicated:  # counts the test user's processes and threads
                    resource.setrlimit(resource.RLIMIT_NPROC, (MAX_PROCESSES, MAX_PROCESSES))
            except (ImportError, ValueError, OSError):
                pass
        return apply

    def reap(self, token: str) -> int:
        """Ends the processes the cases of one submission left running (a daemon that escaped
        its process group): the dedicated user's processes marked with `token`, and those that
        dropped the mark (the cases of other submissions graded at the same time carry their
        own). Nothing when the tests run as the grader's own user. Returns how many."""
        if not self.dedicated or not os.path.isdir("/proc"):
            return 0
        ended = 0
        for _ in range(3):          # a process may fork while the first pass looks
            found = 0
            for entry in os.listdir("/proc"):
                if not entry.isdigit():
                    continue
                try:
                    with open(f"/proc/{entry}/status", "rb") as f:
                        uid = next((line.split()[1] for line in f if line.startswith(b"Uid:")), b"")
                    if int(uid) != self.uid:
                        continue
                    with open(f"/proc/{entry}/environ", "rb") as f:
                        env = f.read().split(b"\0")
                except (OSError, ValueError):
                    continue
                marks = [e for e in env if e.startswith(RUN_VARIABLE.encode() + b"=")]
                if not marks or marks[0] == f"{RUN_VARIABLE}={token}".encode():
                    try:
                        os.kill(int(entry), signal.SIGKILL)
                        found += 1
                    except OSError:
                        pass
            ended += found
            if not found:
                break
            time.sleep(0.05)
        return ended

    def first_readable(self, paths: Sequence[Path], env: Dict[str, str]) -> Optional[Path]:
        """The first of `paths` the user can read, or None (always None when the tests run
        as the grader's own user: it reads everything the grader does)."""
        if not self.dedicated:
            return None
        for path in paths:
            code, _ = run(self.command(["/bin/sh", "-c", 'test -r "$1"', "probe", str(path)]), timeout=30, env=env)
            if code == 0:
                return path
        return None

    def can_reach(self, paths: Sequence[Tuple[Path, str]], env: Dict[str, str]) -> Optional[Path]:
        """The first of `paths` ((path, 'x' to run or enter it, 'r' to read it)) the user
        cannot use, or None."""
        if not self.dedicated:
            return None
        for path, how in paths:
            flag = "-x" if how == "x" else "-r"
            code, _ = run(self.command(["/bin/sh", "-c", f'test {flag} "$1"', "probe", str(path)]), timeout=30,
                          env=env)
            if code != 0:
                return path
        return None


# Each slot of a grading run (slot k of a batch, or the one slot of a single submission)
# runs as a uid of its own that no other process has: SLOT_UIDS + block * BLOCK + k, where
# the block is this run's alone (claim_uid_block: two graders on one machine never share
# one). So a submission's processes cannot signal, trace or read those of another, or of
# another grading run, and all of a slot's processes are ended after each suite without
# touching anyone else's. The uids are not in /etc/passwd; the kernel needs none.
SLOT_UIDS = 3_000_000_000
BLOCK = 64
BLOCKS = 4096


class UidBlock:
    """A block of BLOCK uids held by this grading run: an exclusive lock on a file in a
    folder only root may write, released when the run ends, however it ends."""

    def __init__(self, index: int, handle) -> None:
        self.index = index
        self._handle = handle     # kept open: the lock lives as long as it does

    def uid(self, slot: int) -> int:
        if not 0 <= slot < BLOCK:
            raise GradeError(f"expected at most {BLOCK} slots in one grading run, found slot {slot}; "
                             f"grade with fewer --jobs")
        return SLOT_UIDS + self.index * BLOCK + slot


def claim_uid_block(folder: Path = Path("/run/rt-grader")) -> UidBlock:
    """The first block of uids that no other grading run on this machine holds."""
    import fcntl
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
    except OSError:
        folder = Path(tempfile.gettempdir()) / "rt-grader-uids"
        folder.mkdir(mode=0o700, exist_ok=True)
    info = folder.lstat()
    if not stat_is_private_dir(info):
        raise GradeError(f"{folder}: expected a folder of root's that no one else may write, found one owned "
                         f"by uid {info.st_uid} with mode {info.st_mode & 0o777:o}; remove it")
    for index in range(BLOCKS):
        handle = open(folder / f"block{index}.lock", "a+b")
        try:
            fcntl.flock(handle.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.close()
            continue
        return UidBlock(index, handle)
    raise GradeError(f"expected a free block of test uids in {folder}, found all {BLOCKS} held by running graders")


def stat_is_private_dir(info: os.stat_result) -> bool:
    return stat.S_ISDIR(info.st_mode) and info.st_uid == os.geteuid() and not info.st_mode & 0o022


def slot_user(user: TestUser, index: int, block: Optional[UidBlock]) -> TestUser:
    """The user slot `index` runs as: a uid of its own, from this run's block (only when
    the grader is root, and so `user` is dedicated: the grader's own user otherwise)."""
    if not user.dedicated:
        return user
    prefix = list(user.prefix)
    if block is None or not prefix or not prefix[0].endswith("setpriv"):
        if index == 0:
            return user
        raise GradeError("expected setpriv (util-linux) to run a batch's slots as users of their own, found none; "
                         "install util-linux or grade with --jobs 1")
    uid = block.uid(index)
    try:
        pwd.getpwuid(uid)
        raise GradeError(f"expected uid {uid} to be unused (the grader's slot {index} runs as it), found "
                         f"a user with it")
    except KeyError:
        pass
    prefix = [prefix[0], f"--reuid={uid}", f"--regid={uid}", "--clear-groups", "--no-new-privs", "--"]
    return TestUser(f"{user.name}+{index}", uid, uid, prefix, dedicated=True)


def choose_user(requested: Optional[str]) -> TestUser:
    """The dedicated user when the grader is root (`requested`, else rtgrader), the
    grader's own user otherwise."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        uid = os.getuid() if hasattr(os, "getuid") else 0
        try:
            name = pwd.getpwuid(uid).pw_name
        except (KeyError, NameError):
            name = str(uid)
        return TestUser(name, uid, os.getgid() if hasattr(os, "getgid") else 0)
    name = requested or DEFAULT_USER
    try:
        entry = pwd.getpwnam(name)
    except KeyError:
        raise GradeError(f"expected a user {name} to run the tests as (the grader is root and never runs a "
                         f"submission's code as root), found none; create it with "
                         f"`useradd --system --no-create-home --shell /usr/sbin/nologin {name}` "
                         f"(tools/gradescope/setup.sh does) or pass --run-as USER")
    if entry.pw_uid == 0:
        raise GradeError(f"--run-as {name}: expected an unprivileged user, found uid 0")
    setpriv, runuser = shutil.which("setpriv"), shutil.which("runuser")
    if setpriv:
        prefix = [setpriv, f"--reuid={entry.pw_uid}", f"--regid={entry.pw_gid}", "--clear-groups",
                  "--no-new-privs", "--"]
    elif runuser:
        prefix = [runuser, "-u", name, "--"]
    else:
        raise GradeError("expected setpriv or runuser (util-linux) to run the tests as another user, "
                         "found neither; install util-linux")
    return TestUser(name, entry.pw_uid, entry.pw_gid, prefix, dedicated=True)


def prepare_run_dir(run_dir: Path, user: TestUser) -> Tuple[Path, Path]:
    """run_dir/bin (the test programs, which the user may run but not read) and
    run_dir/home (the user's working folder); returns both."""
    bin_dir, home = run_dir / "bin", run_dir / "home"
    for d in (run_dir, bin_dir):
        d.mkdir(parents=True, exist_ok=True)
        os.chmod(d, 0o711)
    home.mkdir(parents=True, exist_ok=True)
    if user.dedicated:
        os.chown(home, user.uid, user.gid)
    os.chmod(home, 0o700)
    return bin_dir, home


def install_program(source: Path, bin_dir: Path, user: TestUser) -> Path:
    """A copy of a test program the user may run; when the user is dedicated it cannot read
    it (the kernel loads it all the same), so no case reads the compiled code of others."""
    destination = bin_dir / source.name
    tmp = bin_dir / (source.name + ".tmp")
    shutil.copyfile(source, tmp)
    os.chmod(tmp, 0o711 if user.dedicated else 0o755)
    os.replace(tmp, destination)
    return destination


def reap_all(user: TestUser) -> int:
    """Ends every process of a slot's own user, whatever it carries (a slot's uid is its
    alone): none outlives its suite. Returns how many."""
    if not user.dedicated or not os.path.isdir("/proc"):
        return 0
    ended = 0
    for _ in range(5):
        found = 0
        for entry in os.listdir("/proc"):
            if not entry.isdigit():
                continue
            try:
                with open(f"/proc/{entry}/status", "rb") as f:
                    uids = next((line.split()[1:5] for line in f if line.startswith(b"Uid:")), [])
                if str(user.uid).encode() not in uids:
                    continue
                os.kill(int(entry), signal.SIGKILL)
                found += 1
            except (OSError, ValueError):
                continue
        ended += found
        if not found:
            break
        time.sleep(0.05)
    return ended


def case_filter(name: str) -> str:
    """doctest's --test-case filter for this case: a comma separates filters (and only
    doctest 2.4.9 and later read an escaped one), so a comma or a backslash becomes the
    wildcard '?', which matches it in every version."""
    return re.sub(r"[,\\]", "?", name)


def _read_output(f) -> str:
    """The beginning and the end of a case's output file."""
    size = f.seek(0, os.SEEK_END)
    f.seek(0)
    if size <= 2 * OUTPUT_KEPT:
        return f.read().decode("utf-8", "replace")
    head = f.read(OUTPUT_KEPT)
    f.seek(size - OUTPUT_KEPT)
    tail = f.read()
    return (head.decode("utf-8", "replace") + f"\n... ({size - 2 * OUTPUT_KEPT} bytes left out) ...\n"
            + tail.decode("utf-8", "replace"))


def run_case(command: Sequence[str], cwd: Optional[str], timeout: float, memory_mb: int,
             user: Optional[TestUser] = None, env: Optional[Dict[str, str]] = None,
             doctest: bool = False) -> Tuple[str, str, float]:
    """Runs one test case in its own process group; returns (status, output, seconds) with
    status passed, failed, crashed or timeout. With `doctest`, an exit code of 0 passes only
    when doctest's summary reports a case passed and none failed."""
    user = user or TestUser("", 0, 0)
    t0 = time.monotonic()
    # the output goes to a file, not a pipe: a process left running that holds it open does
    # not keep the case waiting, and only its beginning and end are read back
    with tempfile.TemporaryFile() as out:
        try:
            p = subprocess.Popen(user.command(command), cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                                 stdin=subprocess.DEVNULL, start_new_session=True, env=env,
                                 preexec_fn=user.limits(memory_mb) if os.name == "posix" else None)
        except OSError as e:
            return "crashed", f"could not start the test: {e}", 0.0
        try:
            p.wait(timeout=max(timeout, 0.1))
            timed_out = False
        except subprocess.TimeoutExpired:
            timed_out = True
        kill_group(p)          # the case's own processes that are still running
        p.wait()
        text = _read_output(out)
    seconds = time.monotonic() - t0
    if timed_out:
        return "timeout", text + f"\n(stopped: still running after {timeout:.0f} s)", seconds
    if p.returncode == 0:
        if doctest:
            summaries = SUMMARY_RE.findall(text)
            if not summaries:
                return "failed", text + ("\n(the program ended before doctest reported the case: "
                                         "something in it ended the program early)"), seconds
            _, passed, failed = (int(x) for x in summaries[-1])
            if passed < 1 or failed > 0:
                return "failed", text + "\n(doctest ran no case of this name)", seconds
        return "passed", text, seconds
    if p.returncode < 0:
        try:
            name = signal.Signals(-p.returncode).name
        except ValueError:
            name = f"signal {-p.returncode}"
        return "crashed", text + f"\n(crashed: {name})", seconds
    return "failed", text, seconds


def list_cases(program: Path, source: str, user: TestUser, env: Dict[str, str], cwd: Path,
               timeout: float = 60) -> Tuple[List[str], str]:
    """The doctest cases of a suite's program ([] and the reason when they cannot be listed),
    listed by the program itself run as the test user, and checked against its source:
    distinct names, as many as the source's TEST_CASE lines."""
    status, out, _ = run_case([str(program), "--list-test-cases", "--no-version"], str(cwd), timeout, 0,
                              user=user, env=env)
    if status != "passed":
        return [], f"its cases could not be listed ({status}): " + out.strip()[-500:]
    names = [l for l in out.splitlines()
             if l.strip() and not l.startswith("[doctest]") and not l.startswith("=====")]
    if "TEST_CASE_TEMPLATE" not in source:
        expected = len(re.findall(r"^\s*(?:TEST_CASE|TEST_CASE_FIXTURE|SCENARIO)\s*\(", source, re.MULTILINE))
        if len(names) != expected or len(set(names)) != len(names):
            return [], (f"expected {expected} distinct cases, as in its source, found {len(names)} "
                        f"listed by its program")
    return names, ""


@dataclass
class Verdict:
    """What the judge's listener wrote for one case."""
    passed: bool = False
    assertions: int = 0
    failed: int = 0
    complete: bool = False      # the run's last line came
    run_passed: bool = False    # and it says: 1 case passed, none failed


def _read_verdict(f) -> Optional[Verdict]:
    f.seek(0)
    lines = f.read(4096).decode("ascii", "replace").splitlines()
    cases = [l.split("\t") for l in lines if l.startswith("case\t")]
    ends = [l.split("\t") for l in lines if l.startswith("end\t")]
    if len(cases) != 1:
        return None
    try:
        v = Verdict(cases[0][1] == "1", int(cases[0][2]), int(cases[0][3]))
        v.complete = len(ends) == 1
        v.run_passed = v.complete and ends[0][1:3] == ["1", "0"]
    except (IndexError, ValueError):
        return None
    return v


class Processors:
    """Hands each running case the processor with the fewest cases on it, for its judge and
    its server to share (RT_JUDGE_CPU). One per grading run: the submissions of a batch
    draw from the same pool, so two cases share a processor only when there are more
    cases than processors."""

    def __init__(self) -> None:
        cpus = sorted(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else []
        self._load = {cpu: 0 for cpu in cpus}
        self._lock = threading.Lock()

    @contextlib.contextmanager
    def one(self) -> Iterator[Optional[int]]:
        with self._lock:
            cpu = min(self._load, key=lambda c: (self._load[c], c)) if self._load else None
            if cpu is not None:
                self._load[cpu] += 1
        try:
            yield cpu
        finally:
            if cpu is not None:
                with self._lock:
                    self._load[cpu] -= 1


def run_judged(judge: Path, case: str, server: Path, cwd: Path, timeout: float, memory_mb: int,
               user: TestUser, expected_assertions: int, stage: int = 0,
               cpu: Optional[int] = None) -> Tuple[str, str, float, Optional[Verdict]]:
    """Runs one case in its judge, whose calls into the student's code go to `server`
    (started by the judge, confined, as `user`, told it serves `stage`; both on processor
    `cpu` when given); returns (status, output, seconds, verdict) with status passed,
    failed, crashed or timeout."""
    t0 = time.monotonic()
    env = {"PATH": "/usr/bin:/bin", "HOME": str(cwd), "LANG": "C.UTF-8", "LC_ALL": "C.UTF-8",
           "RT_JUDGE_SERVER": str(server), "RT_JUDGE_SECONDS": str(max(1, int(timeout))),
           "RT_JUDGE_MEMORY_MB": str(memory_mb), "RT_JUDGE_STAGE": str(stage)}
    if cpu is not None:
        env["RT_JUDGE_CPU"] = str(cpu)
    if user.dedicated:
        env["RT_JUDGE_UID"], env["RT_JUDGE_GID"] = str(user.uid), str(user.gid)
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as verdict_file:
        fd = verdict_file.fileno()
        env["RT_JUDGE_VERDICT_FD"] = str(fd)
        try:
            p = subprocess.Popen([str(judge), f"--test-case={case_filter(case)}", "--no-version"], cwd=str(cwd),
                                 stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                 start_new_session=True, env=env, pass_fds=(fd,))
        except OSError as e:
            return "crashed", f"could not start the judge: {e}", 0.0, None
        try:
            p.wait(timeout=max(timeout, 0.1))
            timed_out = False
        except subprocess.TimeoutExpired:
            timed_out = True
        kill_group(p)          # the judge's server too: it is in the judge's group
        p.wait()
        text = _read_output(out)
        verdict = _read_verdict(verdict_file)
    seconds = time.monotonic() - t0
    if timed_out:
        return "timeout", text + f"\n(stopped: still running after {timeout:.0f} s)", seconds, verdict
    if p.returncode < 0:
        try:
            name = signal.Signals(-p.returncode).name
        except ValueError:
            name = f"signal {-p.returncode}"
        return "crashed", text + (f"\n(the test itself stopped, {name}: a value your code returned put an index "
                                  f"out of range, or the like)"), seconds, verdict
    if verdict is None or not verdict.complete:
        return "failed", text + "\n(the judge gave no verdict for this case)", seconds, verdict
    if p.returncode == 0 and verdict.passed and verdict.failed == 0 and verdict.run_passed:
        if verdict.assertions < expected_assertions:
            return "failed", text + (f"\n(the case made {verdict.assertions} of the {expected_assertions} checks "
                                     f"it makes with a correct answer)"), seconds, verdict
        return "passed", text, seconds, verdict
    return "failed", text, seconds, verdict
