"""The trees a submission is graded in, prepared once and reused (`--cache DIR`,
`--calibrate`).

    CACHE/                  readable by nobody but the grader, except the paths below
      key                   what the cache was made from (the reference, hidden suites, grader)
      grader.cmake          the grader's addition to rt's build (GRADER_CMAKE)
      tree/                 the reference with every exercise stripped and no instructor-only file
                            (its tests/data may be read by the test user: the suites open it)
      hidden/               the hidden suites (their data/ may be read by the test user)
      slots/K/              one build per submission graded at once (batch grading uses several)
        overlay/stageNN/include/   the headers stage NN's suites compile against
        build/              one CMake build of tree/ (Ninja)

Every stage suite's executable (test_stageNN_*, test_hidden_stageNN_*) compiles against its
own stage's overlay instead of tree/include: the reference's headers with, in the default
mode, the student's regions of stage NN and the reference's regions of every other stage.
A submission rewrites only the overlay files whose text changes (the others keep their
times), so Ninja rebuilds only the suites whose stage the submission touches. The
doctest runner and the configuration are built once, when the slot is made.
"""

from __future__ import annotations

import contextlib
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
from .splice import Composed, compose, split_form

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
import make_kit  # noqa: E402

GRADER_VERSION = "2"       # part of the cache's key, with the grader's own source
MAX_SLOTS = 32

# Included by rt's project() (CMAKE_PROJECT_rt_INCLUDE); at the end of the configuration it
# points each stage suite at its stage's overlay, links the unit that defines the stage's
# functions (see Reference.split), and turns off the compiler's source excerpts (an excerpt
# of a line outside the student's region could show the reference's code).
GRADER_CMAKE = r"""# Written by tools/grade.py (tools/grading/cache.py): each stage suite compiles against
# the headers of its own stage, RT_GRADER_OVERLAYS/stageNN/include.
cmake_language(DEFER CALL _rt_grader_overlays)
function(_rt_grader_overlays)
  if(NOT IS_DIRECTORY "${CMAKE_SOURCE_DIR}/tests")
    return()
  endif()
  get_property(targets DIRECTORY "${CMAKE_SOURCE_DIR}/tests" PROPERTY BUILDSYSTEM_TARGETS)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    set(quiet -fno-diagnostics-show-caret -fdiagnostics-color=never)
  elseif(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    set(quiet -fno-caret-diagnostics -fno-color-diagnostics)
  endif()
  foreach(target IN LISTS targets)
    if(NOT target MATCHES "^test_(hidden_)?stage([0-9][0-9])_")
      continue()
    endif()
    set(stage "${CMAKE_MATCH_2}")
    set(overlay "${RT_GRADER_OVERLAYS}/stage${stage}")
    target_include_directories(${target} BEFORE PRIVATE "${overlay}/include")
    target_compile_options(${target} PRIVATE ${quiet})
    # the stage's functions that are not templates: compiled once, in a unit of their own
    if(EXISTS "${overlay}/impl.cpp")
      if(NOT TARGET rt_grader_impl_stage${stage})
        add_library(rt_grader_impl_stage${stage} OBJECT "${overlay}/impl.cpp")
        target_link_libraries(rt_grader_impl_stage${stage} PRIVATE rt_test_main)
        target_include_directories(rt_grader_impl_stage${stage} BEFORE PRIVATE "${overlay}/impl/include")
        target_compile_options(rt_grader_impl_stage${stage} PRIVATE ${quiet})
        if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
          target_compile_options(rt_grader_impl_stage${stage} PRIVATE -O0)
        endif()
      endif()
      target_link_libraries(${target} PRIVATE rt_grader_impl_stage${stage})
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
        # (file, index of the region in by_file[file]) -> the line that makes a unit emit its
        # function: the regions whose functions compile apart from the tests (splice.split_form)
        self.split: Dict[Tuple[str, int], str] = {}
        count: Dict[int, int] = {}
        for rel, regions in self.by_file.items():
            if not rel.startswith("include/"):
                continue
            lines = self.text(rel).split("\n")
            for k, r in enumerate(regions):
                count[r.stage] = count.get(r.stage, 0) + 1
                form = split_form(lines, r, f"{r.stage:02d}_{count[r.stage]}")
                if form is not None:
                    self.split[(rel, k)] = form

    def text(self, rel: str) -> str:
        if rel not in self._texts:
            self._texts[rel] = (self.root / rel).read_text(encoding="utf-8")
        return self._texts[rel]

    def titles(self) -> Dict[int, str]:
        return {s: ", ".join(Path(f).stem[8:].replace("_", " ") for f in files) for s, files in self.stages.items()}

    def stages_compiled_with_tests(self) -> Set[int]:
        """The stages with an exercise that compiles with the tests that call it (a template)."""
        return {r.stage for rel, regions in self.by_file.items() if rel.startswith("include/")
                for k, r in enumerate(regions) if (rel, k) not in self.split}

    def impl_source(self, stage: int) -> Optional[str]:
        """The unit that defines stage `stage`'s functions that compile apart (None when it
        has none): it includes their headers, whose overlay adds a pointer to each."""
        files = sorted({rel for (rel, k) in self.split if self.by_file[rel][k].stage == stage})
        if not files:
            return None
        return ("// Written by tools/grade.py: the functions of stage %02d that are not templates,\n"
                "// compiled once here instead of in every suite that calls them.\n" % stage +
                "".join(f"#include <{rel[len('include/'):]}>\n" for rel in files))

    def overlay(self, stage: int, body_of, students: Dict[str, object]) -> Tuple[Dict[str, Composed],
                                                                                   Dict[str, Composed]]:
        """Stage `stage`'s headers: those its suites compile against, where the functions of
        the stage that compile apart are declarations, and those of its own unit, where they
        are defined. body_of(region) chooses each region's body: "reference", "stub" or the
        student's."""
        tests, unit = {}, {}
        for rel, regions in self.by_file.items():
            if not rel.startswith("include/"):
                continue
            choice = {k: body_of(r) for k, r in enumerate(regions)}
            apart = {k: self.split[(rel, k)] for k, r in enumerate(regions)
                     if r.stage == stage and (rel, k) in self.split}
            student = students.get(rel)
            tests[rel] = compose(rel, self.text(rel), regions, choice, self.doc_of, student, declare=apart)
            unit[rel] = (compose(rel, self.text(rel), regions, choice, self.doc_of, student, keep=apart)
                         if apart else tests[rel])
        return tests, unit

    def stub_state(self, stage: int) -> Tuple[Dict[str, Composed], Dict[str, Composed]]:
        """Stage `stage`'s headers before any submission: the kit's not-done bodies in that
        stage's regions, the reference's everywhere else."""
        return self.overlay(stage, lambda r: "stub" if r.stage == stage else "reference", {})

    def key(self, hidden: Optional[Path]) -> str:
        h = hashlib.sha256()
        h.update(f"grader {GRADER_VERSION}\n{GRADER_CMAKE}\n".encode())
        for part in sorted(Path(__file__).resolve().parent.glob("*.py")):   # the grader itself
            h.update(part.read_bytes())
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


class Cache:
    def __init__(self, root: Path, reference: Reference, hidden: Optional[Path]):
        self.root = root.resolve()
        self.reference = reference
        self.tree = self.root / "tree"
        self.hidden = self.root / "hidden" if hidden is not None else None
        self.hidden_source = hidden
        self.key = ""

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
            for old in ("tree", "hidden", "slots", "key", "grader.cmake"):
                p = self.root / old
                if p.is_dir():
                    shutil.rmtree(p)
                elif p.exists():
                    p.unlink()
            (self.root / "slots").mkdir(mode=0o700)
            staging = self.root / "tree.tmp"
            shutil.rmtree(staging, ignore_errors=True)
            make_kit.write_tree(self.reference.root, self.reference.plan, staging)
            os.rename(staging, self.tree)
            if self.hidden is not None:
                shutil.copytree(self.hidden_source, self.hidden)
            write_atomically(self.root / "grader.cmake", GRADER_CMAKE.encode(), 0o600)
            _private_tree(self.tree, [self.tree / "tests" / "data"])
            if self.hidden is not None:
                _private_tree(self.hidden, [self.hidden / "data"])
            write_atomically(key_file, (self.key + "\n").encode(), 0o600)

    def readable_paths(self) -> List[Path]:
        """What the test programs open: the suites' data."""
        paths = [self.tree / "tests" / "data"]
        if self.hidden is not None:
            paths.append(self.hidden / "data")
        return [p for p in paths if p.is_dir()]

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

    @contextlib.contextmanager
    def slot(self, jobs: int, timeout: float) -> Iterator["Slot"]:
        """A slot no other grader uses, made when needed (configured, its doctest runner built)."""
        for index in range(MAX_SLOTS):
            path = self.root / "slots" / str(index)
            with _flock(path.parent / f"{index}.lock", blocking=False) as fd:
                if fd is None:
                    continue
                slot = Slot(self, index, path)
                slot.ensure(jobs, timeout)
                yield slot
                return
        raise GradeError(f"{self.root}: expected a free build slot, found {MAX_SLOTS} in use")


class Slot:
    def __init__(self, cache: Cache, index: int, path: Path):
        self.cache = cache
        self.index = index
        self.path = path
        self.build_dir = path / "build"
        self.overlays = path / "overlay"

    def overlay_root(self, stage: int) -> Path:
        """Holds include/ (the headers stage NN's suites compile against), impl/include/ (those
        of its unit) and impl.cpp (the unit)."""
        return self.overlays / f"stage{stage:02d}"

    def unit_root(self, stage: int) -> Path:
        return self.overlay_root(stage) / "impl"

    def ensure(self, jobs: int, timeout: float) -> None:
        ready = self.path / "ready"
        if ready.is_file() and ready.read_text().strip() == self.cache.key:
            return
        log(f"grade: preparing build slot {self.index} in {self.path}")
        shutil.rmtree(self.path, ignore_errors=True)
        self.path.mkdir(parents=True)
        os.chmod(self.path, 0o700)
        reference = self.cache.reference
        for stage in reference.stages:
            unit = reference.impl_source(stage)
            for root in [self.overlay_root(stage)] + ([self.unit_root(stage)] if unit else []):
                for rel in reference.include_files:
                    destination = root / rel
                    destination.parent.mkdir(parents=True, exist_ok=True)
                    shutil.copy2(reference.root / rel, destination)
            if unit:
                (self.overlay_root(stage) / "impl.cpp").write_text(unit, encoding="utf-8")
            self.write_overlay(stage, *reference.stub_state(stage))
        if shutil.which("ninja") is None:
            raise GradeError("expected ninja on PATH, found none; install ninja-build")
        true = shutil.which("true") or "/bin/true"
        configure = ["cmake", "-S", str(self.cache.tree), "-B", str(self.build_dir), "-G", "Ninja",
                     "-DCMAKE_BUILD_TYPE=Release", "-DRT_WERROR=OFF", "-DRT_BUILD_STAGES=OFF",
                     "-DRT_INSTALL=OFF", "-DRT_BUILD_BENCH=OFF", "-DRT_HEADER_CHECK=OFF",
                     f"-DCMAKE_PROJECT_rt_INCLUDE={self.cache.root / 'grader.cmake'}",
                     f"-DRT_GRADER_OVERLAYS={self.overlays}",
                     # the suites' cases are listed by the grader, never by running a program
                     # while building (doctest_discover_tests runs it through this "emulator")
                     f"-DCMAKE_CROSSCOMPILING_EMULATOR={true}"]
        if self.cache.hidden is not None:
            configure.append(f"-DRT_HIDDEN_TESTS_DIR={self.cache.hidden}")
        code, out = run(configure, timeout=timeout)
        if code != 0:
            raise GradeError("the reference does not configure:\n" + "\n".join(out.splitlines()[-30:]))
        code, out = run(["ninja", "-C", str(self.build_dir), "-j", str(jobs), "rt_test_main"], timeout=timeout)
        if code != 0:
            raise GradeError("the reference's doctest runner does not build:\n" + "\n".join(out.splitlines()[-30:]))
        write_atomically(ready, (self.cache.key + "\n").encode(), 0o600)

    def write_overlay(self, stage: int, tests: Dict[str, Composed], unit: Dict[str, Composed]) -> int:
        """Writes the files whose text differs from what the overlay holds (the others keep
        their times, so what includes only them is not rebuilt); returns how many."""
        written = 0
        roots = [(self.overlay_root(stage), tests)]
        if (self.overlay_root(stage) / "impl.cpp").is_file():
            roots.append((self.unit_root(stage), unit))
        for root, files in roots:
            for rel, composed in files.items():
                path = root / rel
                data = composed.text.encode("utf-8")
                try:
                    if path.read_bytes() == data:
                        continue
                except OSError:
                    pass
                write_atomically(path, data, 0o600)
                written += 1
        return written

    def program(self, target: Target) -> Path:
        return self.build_dir / "tests" / target.name

    def build(self, targets: Sequence[Target], jobs: int, timeout: float,
              preexec=None) -> Dict[str, str]:
        """Builds the targets, going on after a failure; returns each target's compiler
        output when it failed ("" when it built)."""
        if not targets:
            return {}
        names = [t.name for t in targets]
        code, out = run(["ninja", "-C", str(self.build_dir), "-k", "0", "-j", str(jobs), *names],
                        timeout=max(timeout, 1), preexec=preexec)
        failed: Dict[str, str] = {}
        block_target, block = None, []

        def close_block() -> None:
            if block_target is not None and block_target not in failed:
                failed[block_target] = "\n".join(block)

        owner_re = r"\b(test_[A-Za-z0-9_]+?|rt_grader_impl_stage[0-9]+)(?:\.dir/|$|\s)"
        for line in out.splitlines():
            m = re.match(r"^FAILED: (.*)$", line)
            if m:
                close_block()
                owner = re.search(owner_re, m.group(1))
                block_target, block = (owner.group(1) if owner else None), []
                continue
            if re.match(r"^\[\d+/\d+\] |^ninja: ", line):
                close_block()
                block_target, block = None, []
                continue
            if block_target is not None:
                block.append(line)
        close_block()
        if code == -1:
            stopped = "the build was stopped: the time budget ran out"
            for name in names:
                failed.setdefault(name, stopped)
        # whatever Ninja would still do is not built, whatever the log said
        code, dry = run(["ninja", "-C", str(self.build_dir), "-n", "-k", "0", *names], timeout=60)
        pending = set(re.findall(owner_re, dry, re.MULTILINE))
        for name in names:
            if name in pending and name not in failed:
                failed[name] = out[-4000:] or "the build did not finish"
        # a stage's unit that does not compile is that stage's suites' error
        for name in names:
            m = re.match(r"test_(?:hidden_)?stage([0-9]{2})_", name)
            unit = f"rt_grader_impl_stage{m.group(1)}" if m else ""
            if unit in failed:
                failed[name] = failed[unit]
        return {name: failed.get(name, "") for name in names}
