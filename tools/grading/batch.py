"""Grading a folder of submissions (grade.py --batch): OUT/<student>/results.json and
junit.xml, and OUT/grades.csv with one row per entry of the folder, whatever happens.

A batch is whole or says so: whatever grading one submission raises (the grader's own
GradeError, an OSError, a RecursionError, anything) becomes that student's row, with the
status `error: <one line reason>`, and the worker goes on with the next submission; an
entry no worker could grade (its build slot could not be made) gets such a row too. The
exit code is 1 when a row is an error, and the last line says how many are.

OUT is the grader's: made here with mode 0700 (the students' results are the instructor's
alone), and refused when it is a symbolic link, is not a folder, is owned by another user,
or lies inside the batch folder. Entries whose names start with "." (.DS_Store, .git) are
not submissions: they get no row, and the output names them.
"""

from __future__ import annotations

import os
import pwd
import shutil
import stat
import threading
import traceback
from pathlib import Path
from typing import Callable, Dict, List, Optional

from .common import GradeError, log, write_atomically
from .report import clean_cell, clean_text, grades_csv, stage_points
from .submission import student_name

OUT_MODE = 0o700
REPORTS = ("results.json", "junit.xml")
RESERVED = {"grades.csv"}
MAX_REASON = 300


def _owner(uid: int) -> str:
    try:
        return f"{pwd.getpwuid(uid).pw_name} (uid {uid})"
    except KeyError:
        return f"uid {uid}"


def prepare_out(out: Path, batch: Path) -> None:
    """Makes OUT (mode 0700), or checks that an OUT from an earlier run is the grader's own."""
    me = os.geteuid()
    inside, around = out.resolve(), batch.resolve()
    if inside == around or around in inside.parents:
        raise GradeError(f"--out {out}: expected a folder outside the batch folder {batch}, found one inside it "
                         f"(it would be graded as a student); choose another --out")
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        os.mkdir(out, OUT_MODE)
    except FileExistsError:
        pass
    except OSError as e:
        raise GradeError(f"--out {out}: expected a folder the grader can make, found {e.strerror}; "
                         f"choose another --out")
    info = os.lstat(out)
    if stat.S_ISLNK(info.st_mode):
        raise GradeError(f"--out {out}: expected a folder the grader owns, found a symbolic link; remove it or "
                         f"choose another --out (the grader makes it)")
    if not stat.S_ISDIR(info.st_mode):
        raise GradeError(f"--out {out}: expected a folder, found a file; remove it or choose another --out")
    if info.st_uid != me:
        raise GradeError(f"--out {out}: expected a folder owned by {_owner(me)}, the user grading, found one owned "
                         f"by {_owner(info.st_uid)}; remove it or choose another --out (the grader makes it)")
    os.chmod(out, OUT_MODE)


def _student_folder(out: Path, student: str) -> Path:
    """OUT/<student>, a folder of the grader's; the reports an earlier run left there are
    removed first, so that a submission that fails now shows none."""
    folder = out / student
    try:
        info = os.lstat(folder)
    except FileNotFoundError:
        os.mkdir(folder, OUT_MODE)
        return folder
    if stat.S_ISLNK(info.st_mode) or not stat.S_ISDIR(info.st_mode) or info.st_uid != os.geteuid():
        found = ("a symbolic link" if stat.S_ISLNK(info.st_mode) else "a file" if not stat.S_ISDIR(info.st_mode)
                 else f"a folder owned by {_owner(info.st_uid)}")
        raise GradeError(f"{folder}: expected a folder of the grader's for this student's reports, found {found}; "
                         f"remove it")
    for name in REPORTS:
        try:
            os.unlink(folder / name)
        except FileNotFoundError:
            pass
    return folder


def one_line(e: BaseException) -> str:
    """An exception as one line of a grades.csv status."""
    text = str(e).strip().splitlines()[0] if str(e).strip() else ""
    if not text:
        text = type(e).__name__
    elif not isinstance(e, GradeError):
        text = f"{type(e).__name__}: {text}"
    text = clean_cell(text)
    return text if len(text) <= MAX_REASON else text[:MAX_REASON - 3] + "..."


def student_names(entries: List[Path]) -> Dict[Path, str]:
    """Each entry's student: the entry's name without its archive suffix, or its whole name
    when that is taken (bob/ and bob.zip) or is one of the files the batch writes."""
    names: Dict[Path, str] = {}
    taken = set(RESERVED)
    for e in entries:
        name = student_name(e)
        if name in taken or not name:
            name = e.name
        k = 2
        while name in taken:
            name, k = f"{e.name}~{k}", k + 1
        names[e] = name
        taken.add(name)
    return names


def grade_batch(ctx, folder: Path, out: Path, work: Path, jobs: int, grade: Callable, report: Callable) -> int:
    """Grades every entry of `folder` with grade(ctx, entry, place, slot, build_jobs, case_jobs)
    and writes its reports with report(ctx, outcome, results_path, junit_path) (grade.py's
    grade_one and write_reports); returns the exit code."""
    try:
        listed = sorted(folder.iterdir(), key=lambda e: e.name)
    except OSError as e:
        raise GradeError(f"{folder}: expected a folder of submissions, found {e.strerror}")
    hidden = [e for e in listed if e.name.startswith(".")]
    entries = [e for e in listed if not e.name.startswith(".")]
    if not entries:
        raise GradeError(f"{folder}: expected submissions (folders or .zip/.tar.gz/.tgz/.tar archives), found none")
    prepare_out(out, folder)
    names = student_names(entries)
    workers = max(1, min(jobs, len(entries)))
    build_jobs = max(1, (os.cpu_count() or 2) // workers)
    rows: Dict[Path, Dict[str, object]] = {}
    pending = list(entries)
    stopped: List[str] = []          # why a worker could not grade (its slot could not be made)
    lock = threading.Lock()

    def take() -> Optional[Path]:
        with lock:
            return pending.pop(0) if pending else None

    def grade_entry(k: int, slot, entry: Path) -> Dict[str, object]:
        student = names[entry]
        row: Dict[str, object] = {"student": student}
        try:
            place = work / f"w{k}" / "current"
            shutil.rmtree(place, ignore_errors=True)
            place.mkdir(parents=True)
            os.chmod(place.parent, 0o711)
            reports = _student_folder(out, student)
            outcome = grade(ctx, entry, place, slot, build_jobs, 1)
            report(ctx, outcome, reports / REPORTS[0], reports / REPORTS[1])
            points = stage_points(outcome.suites)
            row.update({f"stage{s:02d}": f"{p:.2f}" for s, p in points.items()})
            row["total"] = f"{sum(points.values()):.2f}"
            row["status"] = outcome.status
            log(f"grade: {clean_cell(student)}: {row['total']} ({clean_cell(str(outcome.status))}, "
                f"{outcome.seconds:.1f} s)")
        except (Exception, SystemExit) as e:  # noqa: BLE001  a batch is whole: any failure is this row's
            row = {"student": student, "total": "", "status": f"error: {one_line(e)}"}
            log(f"grade: {clean_cell(student)}: error: {one_line(e)}")
            if not isinstance(e, GradeError):
                log(clean_text(traceback.format_exc()))
        return row

    def worker(k: int) -> None:
        try:
            with ctx.cache.slot(build_jobs, ctx.budget) as slot:
                while True:
                    entry = take()
                    if entry is None:
                        return
                    row = grade_entry(k, slot, entry)
                    with lock:
                        rows[entry] = row
        except (Exception, SystemExit) as e:  # noqa: BLE001  the slot: the others go on
            with lock:
                stopped.append(one_line(e))
            log(f"grade: worker {k} stopped: {one_line(e)}")

    threads = [threading.Thread(target=worker, args=(k,), name=f"grade-w{k}") for k in range(workers)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for entry in entries:
        if entry not in rows:
            reason = stopped[0] if stopped else "no worker graded it"
            rows[entry] = {"student": names[entry], "total": "", "status": f"error: not graded: {reason}"}
    table = sorted(rows.values(), key=lambda r: str(r["student"]))
    write_atomically(out / "grades.csv", grades_csv(table, ctx.stages))
    errors = sum(str(r["status"]).startswith("error") for r in table)
    not_graded = sum(str(r["status"]).startswith("not graded") for r in table)
    graded = len(table) - errors - not_graded
    if hidden:
        shown = ", ".join(clean_cell(e.name) for e in hidden[:5]) + (" ..." if len(hidden) > 5 else "")
        one = len(hidden) == 1
        print(f"grade: left out {len(hidden)} hidden {'entry' if one else 'entries'} of {folder} "
              f"({'not a submission' if one else 'not submissions'}, no row): {shown}")
    print(f"grade: {len(table)} rows in {out / 'grades.csv'}: {graded} graded, {not_graded} not graded, "
          f"{errors} {'error' if errors == 1 else 'errors'}" + (" (status error: ..., exit code 1)" if errors else ""),
          flush=True)
    return 1 if errors else 0
