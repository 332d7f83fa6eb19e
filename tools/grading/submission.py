"""A submission: a folder or an archive, unpacked safely, and the folder in it that holds
the student's include/rt."""

from __future__ import annotations

import os
import shutil
import stat
import tarfile
import zipfile
from pathlib import Path, PurePosixPath
from typing import List, Optional, Sequence, Tuple

from .common import SubmissionError

HEADER_SUFFIXES = (".hpp", ".h", ".hh", ".hxx", ".inl", ".ipp", ".tpp")
MAX_SUBMISSION_BYTES = 64 * 1024 * 1024
ARCHIVE_SUFFIXES = (".zip", ".tar.gz", ".tgz", ".tar", ".tar.bz2", ".tar.xz")
SKIPPED_DIRS = {".git", "__pycache__", ".cache", ".vscode", ".idea"}


def _is_build_dir(name: str) -> bool:
    return name in ("build", "out") or name.startswith(("build-", "cmake-build-"))


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
            dirnames[:] = [d for d in dirnames if d not in SKIPPED_DIRS and not _is_build_dir(d)]
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
    if name.endswith(ARCHIVE_SUFFIXES[1:]):
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


def student_name(entry: Path) -> str:
    """A batch entry's student: the folder's name, or the archive's without its suffix."""
    name = entry.name
    for suffix in ARCHIVE_SUFFIXES:
        if entry.is_file() and name.lower().endswith(suffix):
            return name[:-len(suffix)]
    return name


def is_submission(entry: Path) -> bool:
    if entry.name.startswith("."):
        return False
    return entry.is_dir() or (entry.is_file() and entry.name.lower().endswith(ARCHIVE_SUFFIXES))
