"""A batch is whole or says so (tools/grading/batch.py, tools/grading/submission.py,
tools/grading/report.py): what a student hands in cannot stop the grading of the others.

Every attack here is a submission a student can make: an archive 1,100 folders deep, a
member path of 4,200 characters, a zip bomb, a tar with a symbolic and a hard link, member
names with control bytes and bytes that are not UTF-8, a case printing NUL, control
characters, `]]>` and invalid UTF-8. Each asserts the outcome: the submission is refused
with one line `file: expected ..., found ...; hint` (or graded, its links and bad names
left out), grades.csv has one row per entry, junit.xml and results.json parse, and the good
submissions score what they score alone. A fault of the grader's own (an OSError writing a
report, a RecursionError) is that student's row, `error: ...`, and the batch exits 1.

The unpacking, report and worker cases take a few seconds; BatchEndToEnd builds the small
reference of tools/tests/grade_fixture.py and grades one batch of 16 entries (about a
minute on 2 cores).

Run: cd tools/grading/tests && python3 ../../tests/run_suite.py test_batch
(ctest runs it as tools.grading.batch, label tools)
"""

import contextlib
import csv
import gzip
import io
import json
import os
import shutil
import stat
import sys
import tarfile
import tempfile
import unittest
import xml.dom.minidom
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from unittest import mock

TOOLS = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(TOOLS / "tests"))
import grade  # noqa: E402
from grade_fixture import (FIXTURE_HEADER, HIDDEN_SUITE, dedent, have_build_tools,  # noqa: E402
                           make_fixture_reference, run_as_arguments, student_copy, temporary_folder)
from grading import batch, submission  # noqa: E402
from grading.common import GradeError, SubmissionError  # noqa: E402
from grading.report import Case, Suite, clean_cell, gradescope_results, grades_csv, junit_bytes  # noqa: E402

ONE_LINE = r"^[^\n]+: expected [^\n]+, found [^\n]+; [^\n]+$"
# what a case may print: NUL, other control characters, an escape sequence, the end of a
# CDATA section, bytes that are not UTF-8 (and, once decoded with surrogateescape, lone
# surrogates)
NASTY = ("A\x00B\x01\x08\x0b\x0c\x1b[31m]]><![CDATA[&<>\"'\x7f\ufffe\uffff\ud800"
         + b"\xff\xfe\xc3(".decode("utf-8", "surrogateescape") + "Z")


# --------------------------------------------------------------------------
# The attacks, as archives
# --------------------------------------------------------------------------

def good_header() -> bytes:
    return dedent(FIXTURE_HEADER).encode()


def deep_zip(path: Path) -> Path:
    """A zip with a good include/rt and a member 1,100 folders deep."""
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("include/rt/fx.hpp", good_header())
        z.writestr("d/" * 1100 + "x.hpp", "//\n")
    return path


def long_path_zip(path: Path) -> Path:
    """A member path of 4,200 characters (21 folders of 199 characters)."""
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("include/rt/fx.hpp", good_header())
        z.writestr("/".join(["p" * 199] * 21) + "/x.hpp", "//\n")
    assert len(z.namelist()[1]) > 4200
    return path


def zip_bomb(path: Path, mib: int = 200) -> Path:
    """A zip of about 0.2 MiB that unpacks to `mib` MiB of zeros."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("include/rt/fx.hpp", good_header())
        with z.open("include/rt/zeros.hpp", "w", force_zip64=True) as f:
            block = b"\0" * (1 << 20)
            for _ in range(mib):
                f.write(block)
    return path


def lying_zip_bomb(path: Path) -> Path:
    """A zip bomb whose member's entry in the central directory declares 100 bytes."""
    zip_bomb(path, 80)
    data = bytearray(path.read_bytes())
    central = data.rfind(b"PK\x01\x02")           # the last member's entry: zeros.hpp
    assert data[central + 24:central + 28] == (80 << 20).to_bytes(4, "little")
    data[central + 24:central + 28] = (100).to_bytes(4, "little")
    path.write_bytes(bytes(data))
    return path


def tar_gz_bomb(path: Path) -> Path:
    """A tar.gz of about 0.1 MiB holding a member of 100 MiB."""
    class Zeros(io.RawIOBase):
        left = 100 << 20

        def readinto(self, b):
            n = min(len(b), self.left)
            b[:n] = b"\0" * n
            self.left -= n
            return n

    with tarfile.open(path, "w:gz") as t:
        _add(t, "include/rt/fx.hpp", good_header())
        info = tarfile.TarInfo("include/rt/zeros.hpp")
        info.size = 100 << 20
        t.addfile(info, Zeros())
    return path


def long_name_bomb(path: Path) -> Path:
    """A tar.gz whose GNU long-name header declares 1 GiB (tarfile reads it whole)."""
    header = tarfile.TarInfo("././@LongLink")
    header.type = tarfile.GNUTYPE_LONGNAME
    header.size = 1 << 30
    with gzip.open(path, "wb", compresslevel=1) as g:
        g.write(header.tobuf(format=tarfile.GNU_FORMAT)[:512])
        block = b"n" * (1 << 20)
        for _ in range(100):
            g.write(block)
    return path


def _add(t: tarfile.TarFile, name: str, data: bytes) -> None:
    info = tarfile.TarInfo(name)
    info.size = len(data)
    t.addfile(info, io.BytesIO(data))


def links_tar(path: Path) -> Path:
    """A good include/rt beside a symbolic link and a hard link to files of the grader's."""
    with tarfile.open(path, "w") as t:
        _add(t, "include/rt/fx.hpp", good_header())
        for kind, name in ((tarfile.SYMTYPE, "include/rt/shadow.hpp"), (tarfile.LNKTYPE, "include/rt/passwd.hpp")):
            link = tarfile.TarInfo(name)
            link.type = kind
            link.linkname = "/etc/shadow" if kind == tarfile.SYMTYPE else "/etc/passwd"
            t.addfile(link)
        link = tarfile.TarInfo("include")          # a link where a folder comes next
        link.type = tarfile.SYMTYPE
        link.linkname = "/tmp"
        t.addfile(link)
    return path


BAD_NAMES = ["include/rt/a\x01\n\x1b[31mb.hpp", "include/rt/\udcff\udcfe.hpp", "\udce9tude/notes.txt"]


def bad_names_tar(path: Path) -> Path:
    """Member names with control bytes and bytes that are not UTF-8, beside a good header."""
    with tarfile.open(path, "w", format=tarfile.GNU_FORMAT, encoding="utf-8", errors="surrogateescape") as t:
        _add(t, "include/rt/fx.hpp", good_header())
        for name in BAD_NAMES:
            _add(t, name, b"//\n")
    return path


def control_names_zip(path: Path) -> Path:
    """A zip (names not marked UTF-8, read as cp437) with control bytes in a name."""
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("include/rt/fx.hpp", good_header())
        z.writestr("include/rt/x\x01\r\ny\x7f.hpp", "//\n")
    return path


def invalid_utf8_zip(path: Path) -> Path:
    """A zip whose names are marked UTF-8 and are not: Python's zipfile cannot open it."""
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("include/rt/fx.hpp", good_header())
        z.writestr("include/rt/\u00e9.hpp", "//\n")
    path.write_bytes(path.read_bytes().replace("\u00e9".encode(), b"\xff\xfe"))
    return path


def unfiles(root: Path):
    return sorted(p.relative_to(root).as_posix() for p in root.rglob("*") if p.is_file() or p.is_symlink())


# --------------------------------------------------------------------------
# Unpacking
# --------------------------------------------------------------------------

class Unpacking(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="grader-batch-"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def refused(self, make, name, *fragments):
        archive = make(self.tmp / name)
        out = self.tmp / ("out-" + name)
        with self.assertRaises(SubmissionError) as caught:
            submission.unpack(archive, out)
        message = str(caught.exception)
        self.assertRegex(message, ONE_LINE)
        self.assertTrue(message.startswith(name + ": expected "), message)
        for fragment in fragments:
            self.assertIn(fragment, message)
        return out

    def test_a_path_too_deep_is_refused_before_a_folder_is_made(self):
        out = self.refused(deep_zip, "deep.zip", "expected at most 32 folders in a path, found 1100 in")
        self.assertFalse((out / "d").exists())

    def test_a_path_too_long_and_a_name_too_long_are_refused(self):
        self.refused(long_path_zip, "long.zip", "expected paths of at most 1024 bytes, found one of 4205 bytes")

        def long_name(path):
            with zipfile.ZipFile(path, "w") as z:
                z.writestr("include/rt/" + "n" * 300 + ".hpp", "//\n")
            return path
        self.refused(long_name, "name.zip", "expected names of at most 255 bytes in a path, found one of 304")

    def test_zip_bombs_are_refused_before_they_are_written(self):
        out = self.refused(zip_bomb, "bomb.zip", "expected at most 64 MiB unpacked, found \"include/rt/zeros.hpp\" "
                                                 "of 200 MiB")
        self.assertFalse((out / "include/rt/zeros.hpp").exists())
        self.assertLess((self.tmp / "bomb.zip").stat().st_size, 1 << 20)
        # a member that declares 100 bytes: no more than those are read (zipfile stops there and
        # finds the checksum wrong), and the bytes written are counted as well as those declared
        out = self.refused(lying_zip_bomb, "liar.zip", "expected a zip archive the grader can read, found one it "
                                                       "cannot (BadZipFile: Bad CRC-32")
        self.assertLessEqual((out / "include/rt/zeros.hpp").stat().st_size, 100)

    def test_tar_bombs_are_refused(self):
        self.refused(tar_gz_bomb, "bomb.tar.gz", "expected at most 64 MiB unpacked, found \"include/rt/zeros.hpp\"")
        self.refused(long_name_bomb, "name.tar.gz", "expected a tar of at most 84 MiB once decompressed, found more")

    def test_too_many_members_and_a_big_zip_directory_are_refused(self):
        def many(path):
            with zipfile.ZipFile(path, "w") as z:
                for k in range(submission.MAX_MEMBERS + 1):
                    z.writestr(f"f{k}", "")
            return path
        self.refused(many, "many.zip", "expected at most 10000 files and folders, found 10001")
        with mock.patch.object(submission, "MAX_ZIP_DIRECTORY_BYTES", 1000):
            self.refused(many, "many2.zip", "expected a zip directory of at most 1000 bytes, found")

    def test_an_archive_python_cannot_read_is_refused_in_one_line(self):
        self.refused(invalid_utf8_zip, "utf8.zip", "expected a zip archive the grader can read, found one it cannot "
                                                   "(UnicodeDecodeError")

        def method(path):
            with zipfile.ZipFile(path, "w") as z:
                z.writestr("include/rt/fx.hpp", "//\n")
            data = bytearray(path.read_bytes())
            data[8] = 99                                   # the compression method, in both headers
            data[data.find(b"PK\x01\x02") + 10] = 99
            path.write_bytes(bytes(data))
            return path
        self.refused(method, "method.zip", "(NotImplementedError: That compression method is not supported)")

        def truncated(path):
            data = gzip.compress(links_tar(self.tmp / "whole.tar").read_bytes())
            path.write_bytes(data[:len(data) // 2])
            return path
        self.refused(truncated, "cut.tar.gz", "expected a tar archive the grader can read")

        def clash(path):
            with zipfile.ZipFile(path, "w") as z:
                z.writestr("include", "a file")
                z.writestr("include/rt/fx.hpp", "//\n")
            return path
        self.refused(clash, "clash.zip", "expected \"include/rt/fx.hpp\" to unpack as a file, found Not a directory")

    def test_links_are_skipped(self):
        out = self.tmp / "out"
        submission.unpack(links_tar(self.tmp / "links.tar"), out)
        self.assertEqual(unfiles(out), ["include/rt/fx.hpp"])
        self.assertFalse((out / "include").is_symlink())

    def test_bad_names_are_cleaned(self):
        for make, name, expected in (
                (bad_names_tar, "names.tar", ["include/rt/a\ufffd\ufffd\ufffd[31mb.hpp", "include/rt/fx.hpp",
                                              "include/rt/\ufffd\ufffd.hpp", "\ufffdtude/notes.txt"]),
                (control_names_zip, "names.zip", ["include/rt/fx.hpp", "include/rt/x\ufffd\ufffd\ufffdy\ufffd.hpp"])):
            with self.subTest(name=name):
                out = self.tmp / ("out-" + name)
                submission.unpack(make(self.tmp / name), out)
                self.assertEqual(unfiles(out), sorted(expected))
                for rel in unfiles(out):
                    rel.encode("utf-8")            # strict: no surrogate left

    def test_a_folder_holding_one_archive_is_that_archive(self):
        # Gradescope unpacks a .zip into /autograder/submission, but leaves a .tar as it is
        folder = self.tmp / "submission"
        folder.mkdir()
        links_tar(folder / "my-rt.tar")
        out = self.tmp / "out"
        submission.unpack(folder, out)
        self.assertEqual(unfiles(out), ["include/rt/fx.hpp"])
        # two archives and no header: both named
        deep_zip(folder / "other.zip")
        with self.assertRaises(SubmissionError) as caught:
            submission.unpack(folder, self.tmp / "out2")
        self.assertRegex(str(caught.exception), ONE_LINE)
        self.assertIn('found 2 archives ("my-rt.tar", "other.zip") and no header', str(caught.exception))
        # an archive of a kind the grader does not read is named
        other = self.tmp / "rar"
        other.mkdir()
        (other / "my-rt.rar").write_bytes(b"Rar!\x1a\x07\x00")
        submission.unpack(other, self.tmp / "out3")
        with self.assertRaises(SubmissionError) as caught:
            submission.find_rt_folder(self.tmp / "out3", ["fx.hpp"])
        self.assertEqual(str(caught.exception), "my-rt.rar: expected a folder, .zip, .tar.gz, .tgz or .tar, found "
                                                "an archive of another kind; hand in your include/rt folder, or a "
                                                ".zip of it")

    def test_a_folder_too_deep_is_refused(self):
        folder = self.tmp / "s"
        deep = folder.joinpath(*(["d"] * 40))
        deep.mkdir(parents=True)
        (deep / "x.hpp").write_text("//\n")
        with self.assertRaises(SubmissionError) as caught:
            submission.unpack(folder, self.tmp / "out")
        self.assertRegex(str(caught.exception), ONE_LINE)
        self.assertIn("s: expected at most 32 folders in a path, found 33", str(caught.exception))


# --------------------------------------------------------------------------
# Reports
# --------------------------------------------------------------------------

class Reports(unittest.TestCase):
    def suites(self):
        s = Suite(1, False, "load" + NASTY, 10, ["t"])
        s.cases = [Case("case " + NASTY, "failed", NASTY * 3, 0.5), Case("passes", "passed", NASTY, 0.1)]
        broken = Suite(2, True, "rays", 5, ["t"], build_error="include/rt/x.hpp:1:1: error: " + NASTY)
        return [s, broken]

    def test_junit_is_well_formed_whatever_a_case_printed(self):
        data = junit_bytes(self.suites())
        xml.dom.minidom.parseString(data)
        root = ET.fromstring(data)
        failures = [f.text for f in root.iter("failure")]
        self.assertEqual(len(failures), 2)
        self.assertIn("]]><![CDATA[&<>\"'", failures[0])          # kept, escaped by the writer
        self.assertIn("A\\x00B\\x01\\x08\\x0b\\x0c\\x1b[31m", failures[0])
        self.assertIn("\\xff\\xfe\\xc3(Z", failures[0])           # the bytes that are not UTF-8
        self.assertIn("\\ud800", failures[0])
        self.assertIn("\\x00", root.find(".//testcase").get("name"))

    def test_results_json_is_valid_whatever_a_case_printed(self):
        results = gradescope_results(self.suites(), "visible", "top " + NASTY, 3.0)
        text = json.dumps(results, indent=2)
        text.encode("utf-8")                                        # strict
        parsed = json.loads(text)
        json.dumps(parsed, ensure_ascii=False).encode("utf-8")      # strict: no lone surrogate in it
        self.assertIn("]]>", parsed["tests"][0]["output"])
        self.assertIn("\\x00B", parsed["output"])

    def test_grades_csv_keeps_one_line_per_student(self):
        rows = [{"student": "a\nb\udcff", "total": "1.00", "status": "not graded: x\r\ny"},
                {"student": "c", "total": "", "status": "error: z"}]
        text = grades_csv(rows, [1]).decode("utf-8")
        self.assertEqual(len(text.splitlines()), 3)
        parsed = list(csv.DictReader(io.StringIO(text)))
        self.assertEqual(parsed[0]["student"], "a\\x0ab\\xff")
        self.assertEqual(clean_cell("tab\there"), "tab\\x09here")


# --------------------------------------------------------------------------
# The workers, with a grading function of the test's
# --------------------------------------------------------------------------

class FakeSlot:
    def __init__(self, broken):
        self.broken = broken

    def __enter__(self):
        if self.broken:
            raise GradeError("cache/slots/0: expected cmake to configure, found it failed")
        return self

    def __exit__(self, *exc):
        return False


class FakeCache:
    def __init__(self, broken_slots):
        self.broken = list(broken_slots)

    def slot(self, jobs, timeout):
        return FakeSlot(self.broken.pop(0) if self.broken else False)


class FakeContext:
    def __init__(self, broken_slots=()):
        self.cache = FakeCache(broken_slots)
        self.budget = 600
        self.stages = [1]


def fake_grade(ctx, entry, place, slot, build_jobs, case_jobs):
    name = entry.name
    if name.startswith("raise-"):
        kind = {"raise-oserror": OSError(28, "No space left on device"), "raise-recursion": RecursionError(
                "maximum recursion depth exceeded"), "raise-keyerror": KeyError("x"),
                "raise-exit": SystemExit(3), "raise-grade": GradeError("first line\nsecond line")}[name]
        raise kind
    suite = Suite(1, False, "load", 10, ["t"], cases=[Case("c", "passed")])
    return grade.Outcome([suite])


def fake_report(ctx, outcome, results, junit):
    results.write_text("{}")
    junit.write_text("<x/>")


class Workers(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="grader-batch-"))
        self.folder = self.tmp / "batch"
        self.folder.mkdir()

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def run_batch(self, ctx, jobs=2):
        out = io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
            code = batch.grade_batch(ctx, self.folder, self.tmp / "out", self.tmp / "work", jobs, fake_grade,
                                     fake_report)
        rows = list(csv.DictReader(io.StringIO((self.tmp / "out" / "grades.csv").read_text())))
        return code, {r["student"]: r for r in rows}, out.getvalue().splitlines()

    def test_every_exception_is_a_row_and_no_worker_dies(self):
        names = ["ann", "raise-oserror", "bob", "raise-recursion", "cat", "raise-keyerror", "raise-exit",
                 "raise-grade", "notes.txt", "dan.zip", ".DS_Store"]
        for name in names:
            (self.folder / name).mkdir() if "." not in name else (self.folder / name).write_text("x")
        code, rows, lines = self.run_batch(FakeContext())
        self.assertEqual(code, 1)
        self.assertEqual(sorted(rows), sorted(n if n != "dan.zip" else "dan" for n in names if n != ".DS_Store"))
        for name in ("ann", "bob", "cat", "dan", "notes.txt"):
            self.assertEqual((rows[name]["status"], rows[name]["total"]), ("graded", "10.00"))
        self.assertEqual(rows["raise-oserror"]["status"], "error: OSError: [Errno 28] No space left on device")
        self.assertEqual(rows["raise-recursion"]["status"], "error: RecursionError: maximum recursion depth exceeded")
        self.assertEqual(rows["raise-keyerror"]["status"], "error: KeyError: 'x'")
        self.assertEqual(rows["raise-exit"]["status"], "error: SystemExit: 3")
        self.assertEqual(rows["raise-grade"]["status"], "error: first line")
        self.assertIn(".DS_Store", lines[-2])
        self.assertEqual(lines[-1], f"grade: 10 rows in {self.tmp / 'out' / 'grades.csv'}: 5 graded, 0 not graded, "
                                    f"5 errors (status error: ..., exit code 1)")

    def test_a_worker_without_a_slot_leaves_its_share_to_the_others(self):
        for name in ("ann", "bob", "cat"):
            (self.folder / name).mkdir()
        code, rows, lines = self.run_batch(FakeContext(broken_slots=[True]))
        self.assertEqual((code, sorted(rows)), (0, ["ann", "bob", "cat"]))
        self.assertEqual({r["status"] for r in rows.values()}, {"graded"})
        self.assertTrue(lines[-1].endswith("3 graded, 0 not graded, 0 errors"), lines[-1])
        # no slot at all: every entry is a row all the same
        code, rows, lines = self.run_batch(FakeContext(broken_slots=[True, True]))
        self.assertEqual((code, sorted(rows)), (1, ["ann", "bob", "cat"]))
        for r in rows.values():
            self.assertEqual(r["status"], "error: not graded: cache/slots/0: expected cmake to configure, found it "
                                          "failed")

    def test_names_that_collide_get_a_row_each(self):
        for name in ("bob", "grades.csv"):
            (self.folder / name).mkdir()
        for name in ("bob.zip", "bob.tar.gz", "grades.csv.zip"):
            (self.folder / name).write_text("x")
        code, rows, lines = self.run_batch(FakeContext())
        self.assertEqual(sorted(rows), ["bob", "bob.tar.gz", "bob.zip", "grades.csv.zip", "grades.csv~2"])


class OutFolder(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="grader-batch-"))
        self.folder = self.tmp / "batch"
        self.folder.mkdir()

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def refused(self, out, *fragments):
        with self.assertRaises(GradeError) as caught:
            batch.prepare_out(out, self.folder)
        message = str(caught.exception)
        self.assertEqual(len(message.splitlines()), 1)
        self.assertRegex(message, r"^--out [^\n]+: expected [^\n]+, found [^\n]+; [^\n]+$")
        for fragment in fragments:
            self.assertIn(fragment, message)

    def test_out_is_made_closed_to_other_users(self):
        out = self.tmp / "a" / "results"
        batch.prepare_out(out, self.folder)
        self.assertEqual(stat.S_IMODE(out.stat().st_mode), 0o700)
        os.chmod(out, 0o777)                 # a folder of an earlier run, left open: closed again
        batch.prepare_out(out, self.folder)
        self.assertEqual(stat.S_IMODE(out.stat().st_mode), 0o700)

    def test_a_link_a_file_and_a_folder_inside_the_batch_are_refused(self):
        target = self.tmp / "elsewhere"
        target.mkdir()
        (self.tmp / "link").symlink_to(target)
        self.refused(self.tmp / "link", "found a symbolic link; remove it or choose another --out")
        (self.tmp / "file").write_text("x")
        self.refused(self.tmp / "file", "expected a folder, found a file")
        self.refused(self.folder / "results", "expected a folder outside the batch folder")
        self.assertFalse((self.folder / "results").exists())

    @unittest.skipUnless(hasattr(os, "geteuid") and os.geteuid() == 0, "needs root to give a folder to another user")
    def test_a_folder_of_another_user_is_refused(self):
        out = self.tmp / "theirs"
        out.mkdir()
        os.chown(out, 65534, 65534)
        self.refused(out, "expected a folder owned by root (uid 0), the user grading, found one owned by",
                     "uid 65534", "remove it or choose another --out")


# --------------------------------------------------------------------------
# A batch graded end to end
# --------------------------------------------------------------------------

WRONG_STAGE_03 = FIXTURE_HEADER.replace("return n;", "return n + T(1);")
# stage 01 wrong, its exception's message (which the judge prints) holding control
# characters, "]]>" and bytes that are not UTF-8 (a NUL would end what() there: the
# writer's own test, NASTY above, has one)
NOISY = FIXTURE_HEADER.replace(
    "return a + b;",
    "throw rt::error(\"AB\\1\\33[31m]]><![CDATA[\\377\\376\\303(Z\");")


@unittest.skipUnless(have_build_tools(), "needs cmake, ninja and a C++ compiler")
class BatchEndToEnd(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = temporary_folder("batch")
        cls.reference = make_fixture_reference(cls.tmp)
        cls.hidden = cls.tmp / "hidden"
        cls.hidden.mkdir(mode=0o700)
        (cls.hidden / "stage01_more.cpp").write_text(HIDDEN_SUITE)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def common(self):
        return ["--reference", str(self.reference), "--hidden", str(self.hidden), "--cache", str(self.tmp / "cache"),
                "--work", str(self.tmp / "work")] + run_as_arguments()

    def test_attacks_leave_a_whole_batch(self):
        folder = self.tmp / "submissions"
        folder.mkdir()
        student_copy(folder / "ann", FIXTURE_HEADER)                # good: 35
        student_copy(folder / "eve", WRONG_STAGE_03)                # good, stage 03 wrong: 25
        student_copy(folder / "zed", NOISY)                         # stage 01 wrong, loudly: 20
        with zipfile.ZipFile(folder / "ivy.zip", "w") as z:         # good, an archive: 35
            z.writestr("rt/include/rt/fx.hpp", good_header())
        (folder / "gus").mkdir()                                    # a .tar as Gradescope leaves it: 35
        links_tar(folder / "gus" / "gus.tar")
        deep_zip(folder / "deep.zip")
        long_path_zip(folder / "long.zip")
        zip_bomb(folder / "bomb.zip")
        tar_gz_bomb(folder / "tarbomb.tar.gz")
        links_tar(folder / "links.tar")                             # graded, its links left out: 35
        bad_names_tar(folder / "names.tar")                         # graded, its names cleaned: 35
        control_names_zip(folder / "ctl.zip")                       # graded: 35
        invalid_utf8_zip(folder / "utf8.zip")
        (folder / "notes.rar").write_bytes(b"Rar!\x1a\x07\x00")
        student_copy(folder / "oserror", FIXTURE_HEADER)            # its report cannot be written
        student_copy(folder / "recursion", FIXTURE_HEADER)          # the grader recurses too deep
        (folder / ".DS_Store").write_bytes(b"\0\0\0\1Bud1")
        out = self.tmp / "results"
        out.mkdir(mode=0o700)
        (out / "oserror" / "results.json").mkdir(parents=True)     # a folder where the report goes

        original = grade.grade_one

        def grade_one(ctx, entry, *rest):
            if entry.name == "recursion":
                raise RecursionError("maximum recursion depth exceeded while calling a Python object")
            return original(ctx, entry, *rest)

        stdout, stderr = io.StringIO(), io.StringIO()
        with mock.patch.object(grade, "grade_one", grade_one), contextlib.redirect_stdout(stdout), \
                contextlib.redirect_stderr(stderr):
            code = grade.main(["--batch", str(folder), "--out", str(out), "--jobs", "2"] + self.common())
        self.assertEqual(code, 1, stderr.getvalue()[-3000:])
        lines = stdout.getvalue().splitlines()
        self.assertEqual(lines[-1], f"grade: 16 rows in {out / 'grades.csv'}: 8 graded, 6 not graded, 2 errors "
                                    f"(status error: ..., exit code 1)",
                         (out / "grades.csv").read_text(encoding="utf-8", errors="replace"))
        self.assertEqual(lines[-2], f"grade: left out 1 hidden entry of {folder} (not a submission, no row): "
                                    f".DS_Store")

        text = (out / "grades.csv").read_text(encoding="utf-8")
        self.assertEqual(len(text.splitlines()), 17)
        rows = {r["student"]: r for r in csv.DictReader(io.StringIO(text))}
        self.assertEqual(sorted(rows), sorted(e.name if e.suffix in ("", ".rar") else e.name.split(".")[0]
                                              for e in folder.iterdir() if not e.name.startswith(".")))
        totals = {name: r["total"] for name, r in rows.items() if r["status"] == "graded"}
        self.assertEqual(totals, {"ann": "35.00", "eve": "25.00", "zed": "20.00", "ivy": "35.00", "gus": "35.00",
                                  "links": "35.00", "names": "35.00", "ctl": "35.00"})
        statuses = {name: r["status"] for name, r in rows.items()}
        expected = {
            "deep": "not graded: deep.zip: expected at most 32 folders in a path, found 1100 in",
            "long": "not graded: long.zip: expected paths of at most 1024 bytes, found one of 4205 bytes",
            "bomb": "not graded: bomb.zip: expected at most 64 MiB unpacked, found \"include/rt/zeros.hpp\" of 200",
            "tarbomb": "not graded: tarbomb.tar.gz: expected at most 64 MiB unpacked",
            "utf8": "not graded: utf8.zip: expected a zip archive the grader can read, found one it cannot",
            "notes.rar": "not graded: notes.rar: expected a folder, .zip, .tar.gz, .tgz or .tar, found another kind",
            "oserror": "error: IsADirectoryError: [Errno 21] Is a directory:",
            "recursion": "error: RecursionError: maximum recursion depth exceeded",
        }
        for name, start in expected.items():
            self.assertTrue(statuses[name].startswith(start), f"{name}: {statuses[name]}")
            if statuses[name].startswith("not graded"):
                self.assertRegex(statuses[name][len("not graded: "):], ONE_LINE)
                self.assertEqual(rows[name]["total"], "0.00")
        self.assertEqual(stat.S_IMODE(out.stat().st_mode), 0o700)

        # the reports of every graded student parse, whatever their cases printed
        for name in totals:
            with self.subTest(reports=name):
                data = (out / name / "junit.xml").read_bytes()
                xml.dom.minidom.parseString(data)
                ET.fromstring(data)
                results = json.loads((out / name / "results.json").read_text(encoding="utf-8"))
                self.assertEqual(results["score"], float(totals[name]))
        zed = ET.fromstring((out / "zed" / "junit.xml").read_bytes())
        printed = "\n".join(f.text or "" for f in zed.iter("failure"))
        self.assertIn("AB\\x01\\x1b[31m]]><![CDATA[", printed)
        self.assertIn("]]>", json.loads((out / "zed" / "results.json").read_text())["tests"][0]["output"])
        names = json.loads((out / "names" / "results.json").read_text())["output"]
        self.assertIn("include/rt/a\ufffd\ufffd\ufffd[31mb.hpp: a header the kit does not have", names)
        self.assertFalse((out / "recursion" / "results.json").exists())

    def test_an_out_folder_that_is_a_link_is_refused_before_grading(self):
        folder = self.tmp / "one"
        student_copy(folder / "ann", FIXTURE_HEADER)
        target = self.tmp / "target"
        target.mkdir()
        (self.tmp / "out-link").symlink_to(target)
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            code = grade.main(["--batch", str(folder), "--out", str(self.tmp / "out-link")] + self.common())
        self.assertEqual(code, 1)
        self.assertIn("grade: --out " + str(self.tmp / "out-link") + ": expected a folder the grader owns, found a "
                      "symbolic link; remove it or choose another --out", stderr.getvalue())
        self.assertEqual(list(target.iterdir()), [])


if __name__ == "__main__":
    unittest.main()
