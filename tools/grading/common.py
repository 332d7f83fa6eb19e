"""What every part of the grader shares: its errors, running a command, writing a file
atomically, logging."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Callable, Dict, List, Optional, Sequence, Set, Tuple


class GradeError(Exception):
    """The grader itself cannot run (exit 1)."""


class SubmissionError(Exception):
    """The submission cannot be graded: it scores zero with this message."""


def log(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def kill_group(p: subprocess.Popen) -> None:
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except OSError:
        try:
            p.kill()
        except OSError:
            pass


def run(args: Sequence[str], cwd: Optional[Path] = None, timeout: Optional[float] = None,
        env: Optional[Dict[str, str]] = None,
        preexec: Optional[Callable[[], None]] = None) -> Tuple[int, str]:
    """Runs a command in a process group of its own, stdout and stderr together; on a
    timeout the whole group is killed (a build's compilers too) and the code is -1."""
    try:
        p = subprocess.Popen(list(args), cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, start_new_session=True, env=env,
                             preexec_fn=preexec)
    except OSError as e:
        return 127, f"{args[0]}: {e.strerror}"
    try:
        out, _ = p.communicate(timeout=None if timeout is None else max(timeout, 0.1))
        return p.returncode, out.decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        kill_group(p)
        out, _ = p.communicate()
        return -1, out.decode("utf-8", "replace") + f"\n(stopped after {timeout:.0f} s)"


def write_atomically(path: Path, data: bytes, mode: Optional[int] = None) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".tmp-", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        if mode is not None:
            os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


class Deadline:
    """The submission's time budget: every build and case is bounded by what is left."""

    def __init__(self, seconds: float):
        self.seconds = seconds
        self.end = time.monotonic() + seconds

    def left(self) -> float:
        return self.end - time.monotonic()

    def expired(self) -> bool:
        return self.left() <= 0


def parse_stages(text: Optional[str], known: Sequence[int]) -> List[int]:
    """'3', '3,4', '03-05' -> the stages; every stage with tests when text is None."""
    if text is None:
        return sorted(known)
    chosen: Set[int] = set()
    for part in text.split(","):
        part = part.strip()
        m = re.fullmatch(r"(\d{1,2})(?:-(\d{1,2}))?", part)
        if not m:
            raise GradeError(f"--stages {text}: expected stage numbers such as 3 or 3,4 or 3-5, found \"{part}\"")
        first, last = int(m.group(1)), int(m.group(2) or m.group(1))
        chosen.update(range(first, last + 1))
    unknown = sorted(chosen - set(known))
    if unknown:
        raise GradeError(f"--stages {text}: expected stages with tests ({', '.join(f'{s:02d}' for s in known)}), "
                         f"found {', '.join(f'{s:02d}' for s in unknown)}")
    return sorted(chosen)
