#!/usr/bin/env python3
"""stage_table.py - the list of stages, kept in one place: docs/stages/stages.tsv.

    python3 tools/stage_table.py            check that every copy matches the list (exit 1 if not)
    python3 tools/stage_table.py --write    write the copies again from the list
    python3 tools/stage_table.py --self-test

The copies are generated blocks, each between
    <!-- generated: tools/stage_table.py from docs/stages/stages.tsv -->
and <!-- end generated -->:
  - README.md: the table, with what the library does instead of the textbook;
  - tools/kit/README.md (a kit's README): the table, for the student;
  - DEVELOPERS.md: the course order on one line;
  - tools/kit/DEVELOPERS.md (a kit's): the core's order on one line.
Edit docs/stages/stages.tsv, then run --write. The list is checked too: stages
numbered 01, 02, ... in order, each with its program's folder under stages/ and
its page under docs/stages/. In a student kit (no tools/make_kit.py) there is
nothing to check: its README is the kit's own.
"""
import pathlib
import sys

from grading.common import write_atomically  # tools/ is this script's folder, so on sys.path

SOURCE = "docs/stages/stages.tsv"
BEGIN = f"<!-- generated: tools/stage_table.py from {SOURCE} -->"
END = "<!-- end generated -->"
COLUMNS = ["stage", "name", "part", "implements", "library", "program", "page"]


class ListError(Exception):
    pass


def read_stages(root: pathlib.Path) -> list:
    """The rows of the list, each a dict by COLUMNS; ListError names the first bad line."""
    path = root / SOURCE
    rows = []
    header = None
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if not line.strip() or line.startswith("#"):
            continue
        cells = line.split("\t")
        where = f"{SOURCE}:{number}:1"
        if header is None:
            if cells != COLUMNS:
                raise ListError(f"{where}: expected the header line {' TAB '.join(COLUMNS)}, found {line!r}; "
                                f"hint: columns are separated by one tab")
            header = cells
            continue
        if len(cells) != len(COLUMNS):
            raise ListError(f"{where}: expected {len(COLUMNS)} tab-separated cells, found {len(cells)}; "
                            f"hint: an empty cell is two tabs in a row")
        row = dict(zip(COLUMNS, cells))
        expected_number = f"{len(rows) + 1:02d}"
        if row["stage"] != expected_number:
            raise ListError(f"{where}: expected stage {expected_number} (the stages in order), "
                            f"found {row['stage']!r}; hint: number the stages 01, 02, ...")
        if row["part"] not in ("", "going further"):
            raise ListError(f"{where}: expected the part to be empty (the core) or 'going further', "
                            f"found {row['part']!r}")
        folder = root / "stages" / (row["stage"] + "_" + row["program"].split("_", 1)[-1])
        if not row["program"].startswith(f"stage{row['stage']}_") or not folder.is_dir():
            raise ListError(f"{where}: expected a program stage{row['stage']}_NAME built from stages/"
                            f"{row['stage']}_NAME/, found {row['program']!r}; hint: the folder is "
                            f"{folder.relative_to(root).as_posix()}")
        if not (root / "docs" / "stages" / (row["page"] + ".md")).is_file():
            raise ListError(f"{where}: expected a page docs/stages/{row['page']}.md, found none")
        row["line"] = number
        rows.append(row)
    if not rows:
        raise ListError(f"{SOURCE}:1:1: expected a header line and one line per stage, found none")
    return rows


def title(row: dict) -> str:
    return f"{row['stage']} {row['name']}" + (f" ({row['part']})" if row["part"] else "")


def table(rows: list, with_library: bool) -> str:
    lines = ["| stage | " + ("the student implements" if with_library else "you implement") + " | program | page |",
             "|---|---|---|---|"]
    for row in rows:
        implements = row["implements"]
        if with_library and row["library"]:
            implements += f" ({row['library']})"
        lines.append(f"| {title(row)} | {implements} | `{row['program']}` | "
                     f"[{row['page']}](docs/stages/{row['page']}.md) |")
    return "\n".join(lines)


def course_line(rows: list, core_only: bool = False) -> str:
    """01 load scene -> 02 generate rays -> ..., then, going further, 09 ... (or, core_only,
    the core and where the rest is)."""
    core = [r for r in rows if not r["part"]]
    further = [r for r in rows if r["part"]]
    line = " -> ".join(f"{r['stage']} {r['name']}" for r in core)
    if further and core_only:
        line += f"; going further: [the stage pages](docs/stages/) from {further[0]['stage']} on"
    elif further:
        line += ", then, going further, " + " -> ".join(f"{r['stage']} {r['name']}" for r in further)
    return line + "."


COPIES = {
    "README.md": lambda rows: table(rows, with_library=True),
    "tools/kit/README.md": lambda rows: table(rows, with_library=False),
    "DEVELOPERS.md": course_line,
    "tools/kit/DEVELOPERS.md": lambda rows: course_line(rows, core_only=True),
}


def blocks(root: pathlib.Path, rows: list, write: bool) -> list:
    """Problems with each copy (or, with write, none: the copies are rewritten)."""
    problems = []
    for name, render in COPIES.items():
        path = root / name
        text = path.read_text(encoding="utf-8")
        begin = text.find(BEGIN)
        end = text.find(END, begin + 1) if begin >= 0 else -1
        if begin < 0 or end < 0:
            problems.append(f"{name}:1:1: expected a block between {BEGIN!r} and {END!r}, found none; "
                            f"hint: put the two lines where the stages go, then run tools/stage_table.py --write")
            continue
        wanted = BEGIN + "\n" + render(rows) + "\n" + END
        found = text[begin:end + len(END)]
        if found == wanted:
            continue
        if write:
            # whole or not at all: an interrupted --write leaves the page as it was
            write_atomically(path, (text[:begin] + wanted + text[end + len(END):]).encode("utf-8"),
                             mode=path.stat().st_mode & 0o777)
            continue
        line = text.count("\n", 0, begin) + 1
        problems.append(f"{name}:{line}:1: expected the stages of {SOURCE}, found a block that differs; "
                        f"hint: edit {SOURCE}, then run python3 tools/stage_table.py --write")
    return problems


def run(root: pathlib.Path, write: bool) -> int:
    if not (root / "tools" / "make_kit.py").is_file():
        print("a student kit: its README is its own, nothing to check")
        return 0
    try:
        rows = read_stages(root)
    except ListError as e:
        print(e, file=sys.stderr)
        return 1
    problems = blocks(root, rows, write)
    for problem in problems:
        print(problem, file=sys.stderr)
    print(f"{len(rows)} stages in {SOURCE}; {len(COPIES)} copies, {len(problems)} that differ")
    return 1 if problems else 0


def self_test() -> int:
    import contextlib
    import io
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        for sub in ("docs/stages", "stages/01_load_scene", "tools/kit"):
            (root / sub).mkdir(parents=True)
        (root / "tools" / "make_kit.py").write_text("")
        (root / "docs" / "stages" / "01-load-scene.md").write_text("# 01\n")
        (root / SOURCE).write_text("# comment\n" + "\t".join(COLUMNS) + "\n"
                                   "01\tload scene\t\tthe camera\t\tstage01_load_scene\t01-load-scene\n")
        for name in COPIES:
            (root / name).write_text(f"before\n{BEGIN}\nold\n{END}\nafter\n")
        quiet = io.StringIO()
        with contextlib.redirect_stderr(quiet), contextlib.redirect_stdout(quiet):
            stale = run(root, write=False)
            written = run(root, write=True)
            fresh = run(root, write=False)
        kit_table = (root / "tools/kit/README.md").read_text()
        course = (root / "DEVELOPERS.md").read_text()
        if (stale, written, fresh) != (1, 0, 0) or "| 01 load scene | the camera | `stage01_load_scene` |" \
                not in kit_table or "\n01 load scene.\n" not in course or not course.endswith("after\n"):
            print(f"self-test failed: expected a stale copy found (exit 1), then written and found equal "
                  f"(0, 0); found {stale}, {written}, {fresh}:\n{quiet.getvalue()}{kit_table}{course}",
                  file=sys.stderr)
            return 1
        (root / SOURCE).write_text("\t".join(COLUMNS) + "\n02\tsphere\t\tx\t\tstage02_sphere\t01-load-scene\n")
        try:
            read_stages(root)
            print("self-test failed: expected a list that starts at stage 02 to be refused", file=sys.stderr)
            return 1
        except ListError as e:
            if not str(e).startswith(f"{SOURCE}:2:1: expected stage 01"):
                print(f"self-test failed: expected the line of stage 02 named, found: {e}", file=sys.stderr)
                return 1
    print("self-test: a stale copy is found, --write makes it equal, a list out of order is refused")
    return 0


def main(argv: list) -> int:
    root = pathlib.Path(__file__).resolve().parent.parent
    args = argv[1:]
    if args == ["--self-test"]:
        return self_test()
    if args not in ([], ["--write"]):
        print(__doc__, file=sys.stderr)
        return 2
    return run(root, write=args == ["--write"])


if __name__ == "__main__":
    sys.exit(main(sys.argv))
