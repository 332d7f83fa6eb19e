"""The trees a submission is graded in, prepared once and reused (`--cache DIR`,
`--calibrate`).

    CACHE/                  readable by nobody but the grader, except the paths below
      key                   what the cache was made from (the reference, hidden suites, grader)
      grader.cmake          the grader's addition to rt's build (GRADER_CMAKE)
      tree/                 the reference with every exercise stripped and no instructor-only file
      hidden/               the hidden suites
      judge/src/            tools/grading/judge/, the judge's own sources
      judge/overlay/stageNN/   the headers stage NN's judge compiles against (its bodies call
                            the server) and judge_table.cpp (what the judge serves)
      judge/build/          one CMake build of tree/: every suite's program is a judge
      judge/reference/stageNN/  the server built with the reference's bodies (calibration)
      judge/cases.json      each judge's cases, and the assertions each makes with the reference
      public/               what the test user reads to compile a server (every user may):
                            the judge's sources for the server, third_party/, server.flags
      slots/K/              one per submission graded at once (batch grading uses several)
        server/stageNN/     the student's server of stage NN, owned by the slot's test user

A judge holds no line of the student's: the same judges grade every submission, built once.
A submission compiles one small program a stage, its server, as the test user
(tools/grading/judge.py says what goes into it; tools/grading/judge/README.md why).
"""

from __future__ import annotations

import contextlib
import json
import shlex
import fcntl
import hashlib
import os
import re
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, Iterator, List, Optional, Sequence, Set, Tuple

from .common import GradeError, log, run, write_atomically
from . import judge
from .splice import Composed

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
import make_kit  # noqa: E402

GRADER_VERSION = "3"       # part of the cache's key, with the grader's own source
MAX_SLOTS = 32

# Included by rt's project() (CMAKE_PROJECT_rt_INCLUDE); at the end of the configuration it
# makes each stage suite its stage's judge: compiled against the judge's overlay of the
# stage, with front.hpp first, and with what the judge serves and its verdict listener.
# _GLIBCXX_ASSERTIONS: an index the student's values put out of range stops the judge
# (a failed case), never reads past a vector.
GRADER_CMAKE = r"""# Written by tools/grade.py (tools/grading/cache.py): each stage suite is built as its
# stage's judge (tools/grading/judge/README.md).
cmake_language(DEFER CALL _rt_grader_judges)
function(_rt_grader_judges)
  if(NOT IS_DIRECTORY "${CMAKE_SOURCE_DIR}/tests")
    return()
  endif()
  get_property(targets DIRECTORY "${CMAKE_SOURCE_DIR}/tests" PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    if(NOT target MATCHES "^test_(hidden_)?stage([0-9][0-9])_")
      continue()
    endif()
    set(stage "${CMAKE_MATCH_2}")
    set(overlay "${RT_GRADER_JUDGE}/overlay/stage${stage}")
    target_include_directories(${target} BEFORE PRIVATE "${overlay}/include" "${RT_GRADER_JUDGE}/src")
    target_sources(${target} PRIVATE "${overlay}/judge_table.cpp" "${RT_GRADER_JUDGE}/src/verdict.cpp")
    target_compile_options(${target} PRIVATE -include "${RT_GRADER_JUDGE}/src/front.hpp")
    target_compile_definitions(${target} PRIVATE _GLIBCXX_ASSERTIONS)
    if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
      target_compile_options(${target} PRIVATE -O2)   # after the suite's -O0: a judge is built once
    endif()
  endforeach()
endfunction()
"""


@dataclass
class Target:
    name: str         # test_stage03_sphere, test_hidden_stage02_hidden_rays
    stage: int
    hidden: bool
    source: Path      # its .cpp in the cache's tree (or hidden folder)


class Reference:
    """The reference repository: its stages, its regions, its headers."""

    def __init__(self, root: Path, exclude: Sequence[Path] = ()):
        self.root = root.resolve()
        self.stages = make_kit.known_stages(self.root)
        if not self.stages:
            raise GradeError(f"{self.root}: expected a reference with stage suites tests/stageNN_*.cpp, found none")
        try:
            self.plan = make_kit.plan_kit(self.root, set(self.stages))
        except make_kit.KitError as e:
            raise GradeError("the reference's exercise markers are invalid:\n" + "\n".join(e.messages))
        # a cache or work folder inside the reference is not part of it
        skipped = []
        for p in exclude:
            p = p.resolve()
            if self.root in p.parents:
                skipped.append(p.relative_to(self.root).as_posix() + "/")
        self.plan.files = [f for f in self.plan.files if not any(f.startswith(s) for s in skipped)]
        self.regions = sorted(self.plan.stripped + self.plan.solved, key=lambda r: (r.path, r.begin_line))
        self.by_file: Dict[str, List[make_kit.Region]] = {}
        for r in self.regions:
            self.by_file.setdefault(r.path, []).append(r)
        self.doc_of = {s: make_kit.stage_doc(self.root, s) for s in self.stages}
        self.include_files = [f for f in self.plan.files if f.startswith("include/")]
        self._texts: Dict[str, str] = {}

    def text(self, rel: str) -> str:
        if rel not in self._texts:
            self._texts[rel] = (self.root / rel).read_text(encoding="utf-8")
        return self._texts[rel]

    def titles(self) -> Dict[int, str]:
        return {s: ", ".join(Path(f).stem[8:].replace("_", " ") for f in files) for s, files in self.stages.items()}

    def key(self, hidden: Optional[Path]) -> str:
        h = hashlib.sha256()
        h.update(f"grader {GRADER_VERSION}\n{GRADER_CMAKE}\n".encode())
        grading = Path(__file__).resolve().parent
        # what the cache's programs are made by: the judges' sources and build, and the
        # judges' overlays themselves (not splice.py, whose region checks make no judge)
        made_by = [grading / name for name in ("cache.py", "judge.py")]
        for part in made_by + sorted((grading / "judge").glob("*.[ch]pp")):
            h.update(part.name.encode() + b"\0" + part.read_bytes())
        for stage in sorted(self.stages):
            for rel, composed in sorted(judge.judge_overlay(self, stage).items()):
                h.update(f"{stage} {rel}\0".encode() + composed.text.encode("utf-8"))
            h.update(judge.judge_table(self, stage).encode("utf-8"))
        h.update(f"CXX={os.environ.get('CXX', '')} cmake={shutil.which('cmake')} "
                 f"ninja={shutil.which('ninja')}\n".encode())
        for rel in self.plan.files:
            h.update(rel.encode() + b"\0")
            h.update(self.plan.contents[rel].encode("utf-8") if rel in self.plan.contents
                     else (self.root / rel).read_bytes())
        if hidden is not None:
            for f in sorted(hidden.rglob("*")):
                if f.is_file():
                    h.update(b"hidden/" + f.relative_to(hidden).as_posix().encode() + b"\0" + f.read_bytes())
        return h.hexdigest()


def _private_tree(top: Path, readable: Sequence[Path]) -> None:
    """Only the grader may read `top`, except each folder in `readable` (and the way to it),
    which every user may read: what the test programs open at run time."""
    for dirpath, dirnames, filenames in os.walk(top):
        os.chmod(dirpath, 0o700)
        for name in filenames:
            p = os.path.join(dirpath, name)
            if not os.path.islink(p):
                os.chmod(p, 0o600 | (os.stat(p).st_mode & 0o100))
    os.chmod(top, 0o711)
    for folder in readable:
        if not folder.is_dir():
            continue
        walk = folder.parent
        while walk != top and top in walk.parents:
            os.chmod(walk, 0o711)
            walk = walk.parent
        for dirpath, dirnames, filenames in os.walk(folder):
            os.chmod(dirpath, 0o755)
            for name in filenames:
                p = os.path.join(dirpath, name)
                if not os.path.islink(p):
                    os.chmod(p, 0o644)


@contextlib.contextmanager
def _flock(path: Path, blocking: bool = True) -> Iterator[Optional[int]]:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o600)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if blocking else fcntl.LOCK_NB))
        except BlockingIOError:
            yield None
            return
        yield fd
    finally:
        os.close(fd)


# The judge's sources a server compiles with (every user may read them: they are the grader's
# public code, and hold no body of the reference).
SERVER_SOURCES = ("front.hpp", "remote.hpp", "arguments.hpp", "link.hpp", "wire.hpp", "confine.hpp", "server.cpp")


class Cache:
    def __init__(self, root: Path, reference: Reference, hidden: Optional[Path]):
        self.root = root.resolve()
        self.reference = reference
        self.tree = self.root / "tree"
        self.hidden = self.root / "hidden" if hidden is not None else None
        self.hidden_source = hidden
        self.judge = self.root / "judge"
        self.public = self.root / "public"
        self.key = ""
        self._cases: Optional[Dict[str, List[List[object]]]] = None

    # ----------------------------------------------------------------------
    def prepare(self) -> None:
        """Makes the cache's tree when it is missing or was made from other files."""
        self.root.mkdir(parents=True, exist_ok=True)
        os.chmod(self.root, 0o711)
        with _flock(self.root / ".lock"):
            self.key = self.reference.key(self.hidden_source)
            key_file = self.root / "key"
            if key_file.is_file() and key_file.read_text().strip() == self.key and self.tree.is_dir():
                return
            if key_file.exists():
                log(f"grade: {self.root}: made from other files; making it again")
            for old in ("tree", "hidden", "slots", "judge", "public", "key", "grader.cmake"):
                p = self.root / old
                if p.is_dir():
                    shutil.rmtree(p)
                elif p.exists():
                    p.unlink()
            (self.root / "slots").mkdir(mode=0o711)
            staging = self.root / "tree.tmp"
            shutil.rmtree(staging, ignore_errors=True)
            make_kit.write_tree(self.reference.root, self.reference.plan, staging)
            os.rename(staging, self.tree)
            if self.hidden is not None:
                shutil.copytree(self.hidden_source, self.hidden)
            write_atomically(self.root / "grader.cmake", GRADER_CMAKE.encode(), 0o600)
            # the judge: its sources, and each stage's overlay and table
            shutil.copytree(judge.JUDGE_SOURCES, self.judge / "src",
                            ignore=shutil.ignore_patterns("README.md", "__pycache__"))
            for stage in self.reference.stages:
                overlay = self.judge / "overlay" / f"stage{stage:02d}"
                for rel in self.reference.include_files:
                    destination = overlay / rel
                    destination.parent.mkdir(parents=True, exist_ok=True)
                    shutil.copy2(self.reference.root / rel, destination)
                for rel, composed in judge.judge_overlay(self.reference, stage).items():
                    (overlay / rel).write_text(composed.text, encoding="utf-8")
                (overlay / "judge_table.cpp").write_text(judge.judge_table(self.reference, stage), encoding="utf-8")
            # what a server compiles with, for every user
            for name in SERVER_SOURCES:
                destination = self.public / "judge" / name
                destination.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(judge.JUDGE_SOURCES / name, destination)
            if (self.tree / "third_party").is_dir():
                shutil.copytree(self.tree / "third_party", self.public / "third_party")
            _private_tree(self.tree, [self.tree / "tests" / "data"])
            _private_tree(self.judge, [])
            if self.hidden is not None:
                _private_tree(self.hidden, [self.hidden / "data"])
            _public_tree(self.public)
            write_atomically(key_file, (self.key + "\n").encode(), 0o600)

    def targets(self, stages: Set[int]) -> List[Target]:
        out = []
        for stage, files in sorted(self.reference.stages.items()):
            if stage in stages:
                out += [Target(f"test_{Path(f).stem}", stage, False, self.tree / f) for f in files]
        if self.hidden is not None:
            for f in sorted(self.hidden.glob("stage[0-9][0-9]_*.cpp")):
                stage = int(f.name[5:7])
                if stage in stages and stage in self.reference.stages:
                    out.append(Target(f"test_hidden_{f.stem}", stage, True, f))
        return out

    # ----------------------------------------------------------------------
    # the judges, built once
    def judge_program(self, target: Target) -> Path:
        return self.judge / "build" / "tests" / target.name

    def build_judges(self, stages: Set[int], jobs: int, timeout: float) -> None:
        """Configures the judges' build (once) and builds the judges of `stages`."""
        build = self.judge / "build"
        with _flock(self.root / ".judge.lock"):
            if not (build / "build.ninja").is_file():
                if shutil.which("ninja") is None:
                    raise GradeError("expected ninja on PATH, found none; install ninja-build")
                true = shutil.which("true") or "/bin/true"
                configure = ["cmake", "-S", str(self.tree), "-B", str(build), "-G", "Ninja",
                             "-DCMAKE_BUILD_TYPE=Release", "-DRT_WERROR=OFF", "-DRT_BUILD_STAGES=OFF",
                             "-DRT_INSTALL=OFF", "-DRT_BUILD_BENCH=OFF", "-DRT_HEADER_CHECK=OFF",
                             "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON",
                             f"-DCMAKE_PROJECT_rt_INCLUDE={self.root / 'grader.cmake'}",
                             f"-DRT_GRADER_JUDGE={self.judge}",
                             # the cases are listed by the grader, never while building
                             f"-DCMAKE_CROSSCOMPILING_EMULATOR={true}"]
                if self.hidden is not None:
                    configure.append(f"-DRT_HIDDEN_TESTS_DIR={self.hidden}")
                code, out = run(configure, timeout=timeout)
                if code != 0:
                    shutil.rmtree(build, ignore_errors=True)
                    raise GradeError("the reference does not configure:\n" + "\n".join(out.splitlines()[-30:]))
            targets = self.targets(stages)
            if not targets:
                return
            code, out = run(["ninja", "-C", str(build), "-j", str(jobs)] + [t.name for t in targets], timeout=timeout)
            if code != 0:
                raise GradeError("the judges do not build:\n" + "\n".join(out.splitlines()[-30:]))
            self._write_server_flags(build)

    def _write_server_flags(self, build: Path) -> None:
        """The compiler and its options for a server, taken from a judge's own command
        (the dependencies' include folders and definitions), without the cache's folders."""
        commands = json.loads((build / "compile_commands.json").read_text(encoding="utf-8"))
        entry = next((c for c in commands if re.search(r"[/\\]stage\d\d_[^/\\]*\.cpp$", c.get("file", ""))), None)
        if entry is None:
            raise GradeError(f"{build}: expected a stage suite in compile_commands.json, found none")
        words = entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])
        compiler, kept, k = words[0], [], 1
        private = str(self.root)
        while k < len(words):
            w = words[k]
            k += 1
            if w in ("-o", "-c", "-MF", "-MT", "-MQ", "-include", "-x"):
                k += 1
                continue
            if w in ("-I", "-isystem"):
                path, k = words[k], k + 1
                if not path.startswith(private):
                    kept += [w, path]
                continue
            if w.startswith(("-I", "-isystem")):
                if private not in w:
                    kept.append(w)
                continue
            if w.startswith("-D"):
                if not re.match(r"-D(_GLIBCXX_ASSERTIONS|RT_TEST_DATA_DIR|RT_SHARED_DIR|RT_BVH_AVX2)\b", w):
                    kept.append(w)
                continue
            if w.startswith(("-std=", "-m", "-pthread")) or (w.startswith("-f") and "diagnostics" not in w):
                kept.append(w)
        version = run([compiler, "--version"], timeout=60)[1]
        limits = ["-ferror-limit=5"] if "clang" in version.lower() else ["-fmax-errors=5"]
        flags = {"compiler": compiler, "options": kept + ["-O0", "-ftemplate-backtrace-limit=4"] + limits}
        text = (json.dumps(flags, indent=1) + "\n").encode()
        path = self.public / "server.json"
        if path.is_file() and path.read_bytes() == text and (self.public / "pch").is_dir():
            return
        write_atomically(path, text, 0o644)
        self._write_server_pch(flags)

    def _write_server_pch(self, flags: Dict[str, object]) -> None:
        """public/pch: the standard and GLM headers rt and the judge include, precompiled
        with the servers' own options. Parsing them is most of a server's build (3.8 s to
        2.7 s for stage 11's); they hold nothing of the reference. Without it (a compiler
        that cannot, or other options) a server builds from the text, only slower."""
        folder = self.public / "pch"
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True)
        names: Set[str] = set()
        sources = [self.reference.root / rel for rel in self.reference.include_files]
        sources += [judge.JUDGE_SOURCES / n for n in SERVER_SOURCES]
        for path in sources:
            text = path.read_text(encoding="utf-8", errors="replace") if path.is_file() else ""
            # the standard library's own headers (no .h: not the platform's) and GLM's
            names.update(n for n in re.findall(r"(?m)^\s*#\s*include\s*<([\w/.]+)>", text)
                         if re.fullmatch(r"[a-z_]+", n) or re.fullmatch(r"glm/[\w/]+\.hpp", n))
        header = folder / "server_pch.hpp"
        header.write_text("// The headers every server parses, precompiled (tools/grading/cache.py).\n"
                          + "".join(f"#include <{n}>\n" for n in sorted(names)), encoding="utf-8")
        code, out = run([str(flags["compiler"])] + list(flags["options"]) +  # type: ignore[arg-type]
                        ["-pthread", "-x", "c++-header", str(header), "-o", str(header) + ".gch"], timeout=300)
        if code != 0:
            log("grade: the servers' precompiled header does not build; they build without it:\n"
                + "\n".join(out.splitlines()[-5:]))
            shutil.rmtree(folder, ignore_errors=True)
        _public_tree(self.public)

    def server_command(self, source_dir: Path, output: Path) -> List[str]:
        """The command that builds a server from the headers in source_dir/include and
        source_dir/judge_table.hpp."""
        flags = json.loads((self.public / "server.json").read_text(encoding="utf-8"))
        public = self.public
        pch = public / "pch" / "server_pch.hpp"
        first = ["-include", str(pch)] if Path(str(pch) + ".gch").is_file() else []
        return ([flags["compiler"]] + flags["options"] + first +
                ["-I", str(source_dir), "-I", str(source_dir / "include"), "-I", str(public / "judge"),
                 "-I", str(public / "third_party"), "-include", str(public / "judge" / "front.hpp"),
                 str(public / "judge" / "server.cpp"), "-o", str(output), "-static", "-pthread"])

    # ----------------------------------------------------------------------
    # the cases, with what the reference's run of each asserts
    def cases_file(self) -> Path:
        return self.judge / "cases.json"

    def cases(self, target: Target) -> Optional[List[List[object]]]:
        """[[name, assertions, passed], ...] of the target's judge with the reference's
        server, or None when it was not calibrated."""
        if self._cases is None:
            try:
                self._cases = json.loads(self.cases_file().read_text(encoding="utf-8"))
            except (OSError, ValueError):
                self._cases = {}
        return self._cases.get(target.name)

    def forget_cases(self) -> None:
        """cases() reads cases.json again (another grader may have calibrated)."""
        self._cases = None

    def record_cases(self, found: Dict[str, List[List[object]]]) -> None:
        with _flock(self.root / ".judge.lock"):
            try:
                known = json.loads(self.cases_file().read_text(encoding="utf-8"))
            except (OSError, ValueError):
                known = {}
            known.update(found)
            write_atomically(self.cases_file(), (json.dumps(known, indent=1) + "\n").encode(), 0o600)
        self._cases = None

    def reference_server(self, stage: int) -> Path:
        return self.judge / "reference" / f"stage{stage:02d}" / "server"

    @contextlib.contextmanager
    def slot(self, jobs: int, timeout: float) -> Iterator["Slot"]:
        """A slot no other grader uses."""
        for index in range(MAX_SLOTS):
            path = self.root / "slots" / str(index)
            with _flock(path.parent / f"{index}.lock", blocking=False) as fd:
                if fd is None:
                    continue
                path.mkdir(parents=True, exist_ok=True)
                os.chmod(path, 0o711)
                yield Slot(self, index, path)
                return
        raise GradeError(f"{self.root}: expected a free build slot, found {MAX_SLOTS} in use")


def _public_tree(top: Path) -> None:
    for dirpath, dirnames, filenames in os.walk(top):
        os.chmod(dirpath, 0o755)
        for name in filenames:
            p = os.path.join(dirpath, name)
            if not os.path.islink(p):
                os.chmod(p, 0o644)


class Slot:
    """One submission's folder: its servers, built and run as the slot's test user."""

    def __init__(self, cache: Cache, index: int, path: Path):
        self.cache = cache
        self.index = index
        self.path = path

    def server_dir(self, name: str) -> Path:
        """The folder of one server: stageNN, or groupK (a server of several stages)."""
        return self.path / "server" / name

    def prepare(self, uid: Optional[int], gid: Optional[int]) -> None:
        """An empty server folder owned by the test user (uid) when there is one, closed
        to every other user."""
        top = self.path / "server"
        if top.exists():
            shutil.rmtree(top)
        top.mkdir(mode=0o700)
        if uid is not None:
            os.chown(top, uid, gid)

    def write_server(self, name: str, files: Dict[str, Composed], table: str, uid: Optional[int],
                     gid: Optional[int]) -> Path:
        """The sources of the server `name` (server_dir); returns its folder."""
        root = self.server_dir(name)
        root.mkdir(parents=True, exist_ok=True)
        for rel in self.cache.reference.include_files:
            destination = root / rel
            destination.parent.mkdir(parents=True, exist_ok=True)
            if rel in files:
                destination.write_text(files[rel].text, encoding="utf-8")
            else:
                shutil.copyfile(self.cache.reference.root / rel, destination)
        (root / "judge_table.hpp").write_text(table, encoding="utf-8")
        for dirpath, dirnames, filenames in os.walk(root):
            os.chmod(dirpath, 0o755)
            if uid is not None:
                os.chown(dirpath, uid, gid)
            for name in filenames:
                os.chmod(os.path.join(dirpath, name), 0o644)
        return root
