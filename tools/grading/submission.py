"""A submission: a folder or an archive, unpacked safely, and the folder in it that holds
the student's include/rt.

A student controls every byte of a submission (the archive's format, its member names,
their sizes), so unpacking is bounded: at most MAX_MEMBERS files and folders, MAX_DEPTH
folders in a path, MAX_PATH_BYTES bytes in a path and MAX_NAME_BYTES in each of its
parts, MAX_SUBMISSION_BYTES in all (counted from the sizes an archive declares before a
byte is written, and again from the bytes written). Links, devices, absolute paths and
`..` are skipped. Every refusal is a SubmissionError of one line,
`file: expected ..., found ...; hint`, and nothing a submission holds makes unpacking
raise anything else (a fault of the grader's own disk is a GradeError).
"""

from __future__ import annotations

import bz2
import errno
import gzip
import lzma
import os
import re
import stat
import tarfile
import zipfile
from pathlib import Path, PurePosixPath
from typing import BinaryIO, List, Optional, Sequence, Tuple

from .common import GradeError, SubmissionError

HEADER_SUFFIXES = (".hpp", ".h", ".hh", ".hxx", ".inl", ".ipp", ".tpp")
MAX_SUBMISSION_BYTES = 64 * 1024 * 1024
MAX_MEMBERS = 10_000              # files and folders (and links, skipped) of one submission
MAX_DEPTH = 32                    # folders in one member's path
MAX_PATH_BYTES = 1024             # one member's path, in UTF-8
MAX_NAME_BYTES = 255              # one part of a path (the usual file system's limit)
# A zip's central directory is read whole when the archive is opened (about 0.6 KiB of
# memory for each of its 46-byte entries): it is refused beyond what MAX_MEMBERS entries
# with long names could need, before Python reads it.
MAX_ZIP_DIRECTORY_BYTES = 16 * 1024 * 1024
# A tar is read as a stream; all of it, headers included, is at most this many bytes
# once decompressed (a long-name header is read whole into memory: it is bounded too).
MAX_TAR_STREAM_BYTES = MAX_SUBMISSION_BYTES + MAX_MEMBERS * 4 * 512
ARCHIVE_SUFFIXES = (".zip", ".tar.gz", ".tgz", ".tar", ".tar.bz2", ".tar.xz")
# archives the grader does not read, named when a submission holds one and no header
OTHER_ARCHIVE_SUFFIXES = (".rar", ".7z", ".gz", ".bz2", ".xz", ".zst", ".tbz2", ".txz")
SKIPPED_DIRS = {".git", "__pycache__", ".cache", ".vscode", ".idea"}
CHUNK = 64 * 1024
HINT = "hand in your include/rt folder, or a .zip of it"
# what a member's name may not hold: control characters (a line break would split a
# message in two), and the lone surrogates that stand for bytes that are not UTF-8
_UNSHOWABLE_RE = re.compile("[\x00-\x1f\x7f-\x9f\ud800-\udfff\ufffe\uffff]")
# the errors of writing a member that its name or the archive's other members cause
_MEMBER_ERRNOS = {errno.ENAMETOOLONG, errno.ENOTDIR, errno.EISDIR, errno.EEXIST, errno.EILSEQ,
                  errno.EINVAL, errno.ELOOP}


def _is_build_dir(name: str) -> bool:
    return name in ("build", "out") or name.startswith(("build-", "cmake-build-"))


def clean_name(name: str) -> str:
    """A member's name as the grader writes and shows it: each control character and each
    byte that is not UTF-8 becomes U+FFFD."""
    return _UNSHOWABLE_RE.sub("\ufffd", name)


def shown(name: str, limit: int = 60) -> str:
    """A name for a one-line message: cleaned, and cut in the middle when long."""
    name = clean_name(name)
    if len(name) > limit:
        name = name[:limit * 2 // 3] + "..." + name[-(limit // 3):]
    return f'"{name}"'


def _safe_member(name: str) -> Optional[PurePosixPath]:
    path = PurePosixPath(clean_name(name).replace("\\", "/"))
    if path.is_absolute() or ".." in path.parts or not path.parts:
        return None
    if path.parts[0] == "__MACOSX":
        return None
    return path


def _mib(size: int) -> str:
    return f"{size / (1024 * 1024):.0f} MiB" if size >= 1024 * 1024 else f"{size} bytes"


class _Unpacking:
    """The limits of one submission, counted as it is unpacked into `into`."""

    def __init__(self, label: str, into: Path):
        self.label = label            # the file named in messages: the archive's or folder's name
        self.into = into
        self.members = 0
        self.total = 0

    def refuse(self, expected: str, found: str, hint: str = HINT) -> SubmissionError:
        return SubmissionError(f"{self.label}: expected {expected}, found {found}; {hint}")

    def member(self, name: str) -> None:
        """Counts one member and checks its name's length and depth."""
        self.members += 1
        if self.members > MAX_MEMBERS:
            raise self.refuse(f"at most {MAX_MEMBERS} files and folders", "more")
        parts = [p for p in clean_name(name).replace("\\", "/").split("/") if p not in ("", ".")]
        if len(parts) - 1 > MAX_DEPTH:
            raise self.refuse(f"at most {MAX_DEPTH} folders in a path", f"{len(parts) - 1} in {shown(name)}")
        size = len("/".join(parts).encode("utf-8"))
        if size > MAX_PATH_BYTES:
            raise self.refuse(f"paths of at most {MAX_PATH_BYTES} bytes", f"one of {size} bytes, {shown(name)}")
        for part in parts:
            size = len(part.encode("utf-8"))
            if size > MAX_NAME_BYTES:
                raise self.refuse(f"names of at most {MAX_NAME_BYTES} bytes in a path",
                                  f"one of {size} bytes in {shown(name)}")

    def declare(self, name: str, size: int) -> None:
        """A member's declared size, counted before any of it is written."""
        if size < 0 or self.total + size > MAX_SUBMISSION_BYTES:
            before = f" after {_mib(self.total)} of other files" if self.total else ""
            raise self.refuse(f"at most {_mib(MAX_SUBMISSION_BYTES)} unpacked",
                              f"{shown(name)} of {_mib(size)}{before}")

    def write(self, target: PurePosixPath, source: BinaryIO) -> None:
        """Writes one member, counting the bytes as they come (a zip can declare fewer)."""
        destination = self.into.joinpath(*target.parts)
        try:
            destination.parent.mkdir(parents=True, exist_ok=True)
            dst = open(destination, "wb")
        except OSError as e:
            raise self._write_error(target, e)
        with dst:
            while True:
                chunk = source.read(CHUNK)        # a read error: the caller's (an unreadable archive)
                if not chunk:
                    break
                self.total += len(chunk)
                if self.total > MAX_SUBMISSION_BYTES:
                    raise self.refuse(f"at most {_mib(MAX_SUBMISSION_BYTES)} unpacked",
                                      f"more once {shown(str(target))} is unpacked")
                try:
                    dst.write(chunk)
                except OSError as e:
                    raise self._write_error(target, e)

    def _write_error(self, target: PurePosixPath, e: OSError) -> Exception:
        if e.errno in _MEMBER_ERRNOS:
            return self.refuse(f"{shown(str(target))} to unpack as a file",
                               f"{e.strerror or e} (a file and a folder of one name?)")
        return GradeError(f"{self.into}: expected to write the unpacked submission, found {e.strerror or e}; "
                          f"free some space or choose another --work")


def unpack(submission: Path, into: Path) -> None:
    """Copies or extracts the submission into `into`: regular files only, no links,
    no paths outside it, within the limits above. A folder that holds no header and one
    archive (a .tar uploaded to Gradescope, which unpacks only a .zip) is that archive."""
    into.mkdir(parents=True, exist_ok=True)
    if submission.is_dir():
        _unpack_folder(submission, into)
        return
    if not submission.is_file():
        found = "another kind of file" if os.path.lexists(submission) else "nothing of that name"
        raise SubmissionError(f"{clean_name(submission.name)}: expected a folder or an archive, found {found}; {HINT}")
    _unpack_archive(submission, into)


def _unpack_folder(submission: Path, into: Path) -> None:
    job = _Unpacking(clean_name(submission.name) or "submission", into)
    files: List[Tuple[Path, PurePosixPath]] = []
    headers = 0
    archives: List[Path] = []

    def walk_error(e: OSError) -> None:
        raise GradeError(f"{e.filename}: expected a folder the grader can read, found {e.strerror}")

    for dirpath, dirnames, filenames in os.walk(submission, onerror=walk_error):
        here = Path(dirpath)
        rel = here.relative_to(submission)
        dirnames[:] = sorted(d for d in dirnames if d not in SKIPPED_DIRS and not _is_build_dir(d))
        for d in dirnames:                       # checked before os.walk goes into them
            job.member((rel / d).as_posix())
        for name in sorted(filenames):
            source = here / name
            job.member((rel / name).as_posix())
            try:
                info = source.lstat()
            except OSError:
                continue
            if not stat.S_ISREG(info.st_mode):
                continue                         # links, devices, pipes
            target = _safe_member((rel / name).as_posix())
            if target is None:
                continue
            files.append((source, target))
            if name.endswith(HEADER_SUFFIXES):
                headers += 1
            elif rel == Path(".") and name.lower().endswith(ARCHIVE_SUFFIXES):
                archives.append(source)
    if headers == 0 and len(archives) == 1:
        _unpack_archive(archives[0], into)
        return
    if headers == 0 and len(archives) > 1:
        names = ", ".join(shown(a.name, 40) for a in archives[:4])
        raise job.refuse("your include/rt folder or one archive of it", f"{len(archives)} archives ({names}) and "
                         f"no header", "hand in one of them")
    for source, target in files:
        with open(source, "rb") as src:
            job.declare(str(target), os.fstat(src.fileno()).st_size)
            job.write(target, src)


def _unpack_archive(submission: Path, into: Path) -> None:
    label = clean_name(submission.name)
    job = _Unpacking(label, into)
    name = submission.name.lower()
    is_zip = name.endswith(".zip")
    if not is_zip and not name.endswith(ARCHIVE_SUFFIXES[1:]):
        raise job.refuse("a folder, .zip, .tar.gz, .tgz or .tar", "another kind of file")
    size = submission.stat().st_size
    if size > MAX_SUBMISSION_BYTES:
        raise job.refuse(f"an archive of at most {_mib(MAX_SUBMISSION_BYTES)}", _mib(size))
    kind = "zip" if is_zip else "tar"
    try:
        with open(submission, "rb") as raw:
            if is_zip:
                _unpack_zip(job, raw)
            else:
                _unpack_tar(job, raw)
    except (SubmissionError, GradeError):
        raise
    except Exception as e:  # noqa: BLE001  whatever the archive makes Python's readers raise
        reason = clean_name(str(e).splitlines()[0] if str(e) else "")[:160]
        raise job.refuse(f"a {kind} archive the grader can read", f"one it cannot ({type(e).__name__}"
                         f"{': ' + reason if reason else ''})", "make it again, or hand in the folder")


def _unpack_zip(job: _Unpacking, raw: BinaryIO) -> None:
    end = getattr(zipfile, "_EndRecData", None)      # the record that says how long the directory is
    if end is not None:
        record = end(raw)
        if record is not None and record[zipfile._ECD_SIZE] > MAX_ZIP_DIRECTORY_BYTES:
            raise job.refuse(f"a zip directory of at most {_mib(MAX_ZIP_DIRECTORY_BYTES)}",
                             _mib(record[zipfile._ECD_SIZE]))
        raw.seek(0)
    with zipfile.ZipFile(raw) as archive:
        infos = archive.infolist()
        if len(infos) > MAX_MEMBERS:
            raise job.refuse(f"at most {MAX_MEMBERS} files and folders", f"{len(infos)}")
        for info in infos:
            job.member(info.filename)
            mode = (info.external_attr >> 16) & 0o170000
            target = _safe_member(info.filename)
            if info.is_dir() or target is None or mode in (stat.S_IFLNK, stat.S_IFCHR, stat.S_IFBLK, stat.S_IFIFO,
                                                           stat.S_IFSOCK):
                continue
            job.declare(info.filename, info.file_size)
            with archive.open(info) as src:
                job.write(target, src)


class _BoundedReader:
    """A decompressed stream that ends the unpacking once it has given `limit` bytes."""

    def __init__(self, stream: BinaryIO, job: _Unpacking, limit: int):
        self.stream, self.job, self.limit, self.given = stream, job, limit, 0

    def read(self, size: int = -1) -> bytes:
        if size is None or size < 0 or size > self.limit - self.given:
            size = self.limit - self.given + 1
        data = self.stream.read(size)
        self.given += len(data)
        if self.given > self.limit:
            raise self.job.refuse(f"a tar of at most {_mib(self.limit)} once decompressed", "more")
        return data


def _unpack_tar(job: _Unpacking, raw: BinaryIO) -> None:
    magic = raw.read(6)
    raw.seek(0)
    if magic.startswith(b"\x1f\x8b"):
        stream: BinaryIO = gzip.GzipFile(fileobj=raw, mode="rb")
    elif magic.startswith(b"BZh"):
        stream = bz2.BZ2File(raw)
    elif magic.startswith(b"\xfd7zXZ\x00"):
        stream = lzma.LZMAFile(raw)
    else:
        stream = raw
    with stream, tarfile.open(fileobj=_BoundedReader(stream, job, MAX_TAR_STREAM_BYTES), mode="r|",
                              encoding="utf-8", errors="surrogateescape") as archive:
        for member in archive:
            job.member(member.name)
            job.declare(member.name, member.size)
            target = _safe_member(member.name)
            if not member.isfile() or target is None:
                continue  # links, devices, folders and paths outside are skipped
            src = archive.extractfile(member)
            if src is None:
                continue
            with src:
                job.write(target, src)


def find_rt_folder(root: Path, reference_headers: Sequence[str]) -> Path:
    """The submission's rt header folder: include/rt if there is one, else the
    shallowest folder named rt with headers in it or in its folders (rt's layers:
    rt/intersection/sphere.hpp), else a folder holding rt's headers."""
    candidates: List[Tuple[int, int, str, Path]] = []
    known = set(reference_headers)
    headers_in = {Path(dirpath): [f for f in filenames if f.endswith(HEADER_SUFFIXES)]
                  for dirpath, _, filenames in os.walk(root)}
    with_headers = set()  # the folders with a header in them or below
    for here, headers in headers_in.items():
        while headers and here not in with_headers and here != root.parent:
            with_headers.add(here)
            here = here.parent
    for here in with_headers:
        headers = headers_in[here]
        depth = len(here.relative_to(root).parts)
        if here.name == "rt" and here.parent.name == "include":
            candidates.append((0, depth, str(here), here))
        elif here.name == "rt":
            candidates.append((1, depth, str(here), here))
        elif known & set(headers):
            candidates.append((2, depth, str(here), here))
    if not candidates:
        others = sorted(p.name for p in root.iterdir()
                        if p.is_file() and p.name.lower().endswith(OTHER_ARCHIVE_SUFFIXES))
        if others:
            raise SubmissionError(f"{clean_name(others[0])}: expected a folder, .zip, .tar.gz, .tgz or .tar, found "
                                  f"an archive of another kind; {HINT}")
        raise SubmissionError("no include/rt folder (or rt's headers) found in the submission; "
                              "hand in your include/rt folder, or the whole repository")
    return min(candidates)[3]


def reference_path(name: str, reference_files: Sequence[str]) -> Optional[str]:
    """The reference's path (include/rt/...) for a header handed in as `name`, relative to
    the submission's rt folder: the same path, else the one reference header of that file
    name (a header handed in loose, or by its path before rt's folders, rt/sphere.hpp for
    rt/intersection/sphere.hpp), else None."""
    rel = f"include/rt/{name}"
    if rel in reference_files:
        return rel
    base = name.rsplit("/", 1)[-1]
    same = [f for f in reference_files if f.startswith("include/rt/") and f.rsplit("/", 1)[-1] == base]
    return same[0] if len(same) == 1 else None


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
