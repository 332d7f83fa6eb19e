"""kits.repository - what a kit is made from: the stages (tests/stageNN_*.cpp),
their pages (docs/stages/NN-*.md), the repository's files, the manifest
tools/kit_manifest.json (what is instructor-only), and the regions of every
file that may hold them.
"""

from __future__ import annotations

import fnmatch
import json
import os
import re
import subprocess
from pathlib import Path
from typing import Dict, Iterable, List, Optional

from .regions import KitError, Region, scan_file

MANIFEST_NAME = "tools/kit_manifest.json"
STAGE_TEST_RE = re.compile(r"^stage(?P<stage>[0-9]{2})_\w+\.cpp$")
STAGE_DOC_RE = re.compile(r"^(?P<stage>[0-9]{2})-[\w.-]+\.md$")
SOURCE_SUFFIXES = (".hpp", ".h", ".hh", ".hxx", ".ipp", ".inl", ".cpp", ".cc", ".cxx")

# Folders never copied, whatever the manifest says: build trees and VCS data.
ALWAYS_SKIPPED_DIRS = {".git", "__pycache__", ".cache", ".vscode", ".idea"}
BUILD_DIR_RE = re.compile(r"^(build|build-.*|cmake-build-.*|out)$")


# --------------------------------------------------------------------------
# The repository: stages, doc pages, files, manifest
# --------------------------------------------------------------------------

def known_stages(root: Path) -> Dict[int, List[str]]:
    """Stage number -> its test files tests/stageNN_*.cpp (relative paths)."""
    stages: Dict[int, List[str]] = {}
    tests = root / "tests"
    if tests.is_dir():
        for entry in sorted(tests.iterdir()):
            m = STAGE_TEST_RE.match(entry.name)
            if m and entry.is_file():
                stages.setdefault(int(m.group("stage")), []).append(f"tests/{entry.name}")
    return stages


def stage_doc(root: Path, stage: int) -> Optional[str]:
    """docs/stages/NN-<name>.md, or None when the stage has no page yet."""
    docs = root / "docs" / "stages"
    if docs.is_dir():
        for entry in sorted(docs.iterdir()):
            m = STAGE_DOC_RE.match(entry.name)
            # NN-going-further.md is the page after the lesson, never the lesson
            if m and int(m.group("stage")) == stage and not entry.name.endswith("-going-further.md"):
                return f"docs/stages/{entry.name}"
    return None


def load_manifest(root: Path) -> dict:
    path = root / MANIFEST_NAME
    manifest = {"exercise_roots": ["include", "stages"], "instructor_only": []}
    if path.is_file():
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except json.JSONDecodeError as e:
            raise KitError([f"{MANIFEST_NAME}:{e.lineno}:{e.colno}: expected JSON, found {e.msg}"])
        for key in manifest:
            if key in data:
                if not isinstance(data[key], list) or not all(isinstance(s, str) for s in data[key]):
                    raise KitError([f"{MANIFEST_NAME}:1:1: expected \"{key}\": a list of strings, "
                                    f"found {json.dumps(data[key])}"])
                manifest[key] = data[key]
    return manifest


def is_instructor_only(rel: str, patterns: Iterable[str]) -> bool:
    for pattern in patterns:
        if pattern.endswith("/"):
            if rel.startswith(pattern) or fnmatch.fnmatchcase(rel.split("/")[0] + "/", pattern):
                return True
            # a folder pattern with wildcards, e.g. tests/*/hidden/
            parts = rel.split("/")
            for k in range(1, len(parts)):
                if fnmatch.fnmatchcase("/".join(parts[:k]) + "/", pattern):
                    return True
        elif fnmatch.fnmatchcase(rel, pattern):
            return True
    return False


def repository_files(root: Path) -> List[str]:
    """The files of the repository: git's tracked and untracked-but-not-ignored
    files when `root` is a git work tree, else every file outside build folders."""
    try:
        out = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--cached", "--others",
                              "--exclude-standard"], capture_output=True, check=True)
        if (root / ".git").exists():
            files = sorted({f for f in out.stdout.decode("utf-8").split("\0") if f})
            return [f for f in files if (root / f).is_file() and not _in_skipped_dir(f)]
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in ALWAYS_SKIPPED_DIRS
                             and not BUILD_DIR_RE.match(d) and not d.startswith("."))
        for name in sorted(filenames):
            rel = Path(dirpath, name).relative_to(root).as_posix()
            files.append(rel)
    return files


def _in_skipped_dir(rel: str) -> bool:
    parts = rel.split("/")[:-1]
    return any(p in ALWAYS_SKIPPED_DIRS or BUILD_DIR_RE.match(p) for p in parts)


def exercise_files(files: Iterable[str], manifest: dict) -> List[str]:
    roots = [r.rstrip("/") + "/" for r in manifest["exercise_roots"]]
    return [f for f in files if f.endswith(SOURCE_SUFFIXES) and any(f.startswith(r) for r in roots)
            and not is_instructor_only(f, manifest["instructor_only"])]


def scan_repository(root: Path, files: Optional[List[str]] = None) -> List[Region]:
    """Every region of the repository; raises KitError listing every marker error."""
    manifest = load_manifest(root)
    files = repository_files(root) if files is None else files
    stages = set(known_stages(root))
    errors: List[str] = []
    regions: List[Region] = []
    for rel in exercise_files(files, manifest):
        try:
            text = (root / rel).read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        regions.extend(scan_file(rel, text, stages, errors))
    if errors:
        raise KitError(errors)
    return regions
