#!/usr/bin/env python3
"""make_autograder.py - the zip to upload to Gradescope as a programming assignment's autograder.

    python3 tools/gradescope/make_autograder.py autograder.zip [--hidden tests/hidden]
            [--stages 3,4] [--weights FILE] [--cumulative] [--budget SECONDS]

The zip holds, at its root, setup.sh and run_autograder (from this folder), the reference
repository under rt/ (without build folders and without the hidden tests), the hidden
suites under hidden/, and grade_args: the options every grading run takes (--stages: only
the stages of this assignment are graded and shown; stages a kit hands out solved score
nothing). --weights FILE ships another weights file as weights.json. The zip may be written
inside the repository: it never goes into a later zip. See docs/instructor-guide.md.
Python 3 standard library only.
"""

import argparse
import sys
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
import make_kit  # noqa: E402
from grading.common import GradeError, parse_stages  # noqa: E402
from grading.weights import load_weights  # noqa: E402


def is_autograder_zip(path: Path) -> bool:
    """An earlier output of this script (left in the repository): never copied into a zip."""
    if not path.name.lower().endswith(".zip"):
        return False
    try:
        with zipfile.ZipFile(path) as z:
            names = set(z.namelist())
    except (zipfile.BadZipFile, OSError):
        return False
    return {"setup.sh", "run_autograder"} <= names


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="the zip to write")
    parser.add_argument("--source", default=str(make_kit.DEFAULT_SOURCE), help="the reference repository")
    parser.add_argument("--hidden", help="folder of hidden suites (default: <source>/tests/hidden if present)")
    parser.add_argument("--stages", help="grade only these stages, e.g. 3 or 3,4 or 3-5 (default: every stage)")
    parser.add_argument("--weights", help="the weights file to grade with (default: <source>/tools/weights.json)")
    parser.add_argument("--cumulative", action="store_true",
                        help="grade every stage with the student's code of every stage (default: each stage alone)")
    parser.add_argument("--budget", type=float, help="seconds a submission may take in all (default: grade.py's, 600)")
    args = parser.parse_args(argv)
    source = Path(args.source).resolve()
    hidden = Path(args.hidden).resolve() if args.hidden else source / "tests" / "hidden"
    output = Path(args.output).resolve()
    tmp = output.with_name(output.name + ".tmp-zip")

    grade_args = []
    try:
        if args.stages:
            stages = parse_stages(args.stages, sorted(make_kit.known_stages(source)))
            grade_args += ["--stages", ",".join(str(s) for s in stages)]
        if args.weights:
            load_weights(Path(args.weights))     # refuse a broken file now, not on Gradescope
    except GradeError as e:
        print(f"make_autograder: {e}", file=sys.stderr)
        return 2
    if args.cumulative:
        grade_args.append("--cumulative")
    if args.budget is not None:
        grade_args += ["--budget", f"{args.budget:g}"]

    skipped = {output, tmp}
    count = 0
    output.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for name in ("setup.sh", "run_autograder"):
            info = zipfile.ZipInfo(name)
            info.external_attr = 0o100755 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, (HERE / name).read_bytes())
        if grade_args:
            z.writestr("grade_args", "".join(a + "\n" for a in grade_args))
        if args.weights:
            z.write(Path(args.weights), "weights.json")
        for rel in make_kit.repository_files(source):
            path = source / rel
            if rel.startswith("tests/hidden/") or path.resolve() in skipped or is_autograder_zip(path):
                continue
            z.write(path, f"rt/{rel}")
            count += 1
        if hidden.is_dir():
            for f in sorted(hidden.rglob("*")):
                if f.is_file():
                    z.write(f, f"hidden/{f.relative_to(hidden).as_posix()}")
    tmp.replace(output)
    print(f"make_autograder: wrote {output}: setup.sh, run_autograder, {count} reference files"
          + (f", hidden suites from {hidden}" if hidden.is_dir() else ", no hidden suites")
          + (f"; grades with {' '.join(grade_args)}" if grade_args else "; grades every stage"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
