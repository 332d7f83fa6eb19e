#!/usr/bin/env python3
"""Holds scenes/README.md's table to the scenes it describes.

Every scenes/*.scene has one row, every row names a scene that exists, and each
row's command runs a stage program that exists (stages/NN_name, built as
stageNN_name) on that scene. Usage: check_scenes.py REPO_ROOT. Prints one line
per problem, exits 1.
"""
import pathlib
import re
import sys


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    page = root / "scenes" / "README.md"
    lines = page.read_text(encoding="utf-8").splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith("<!-- scenes:")), None)
    if start is None:
        print(f"{page}: expected the '<!-- scenes:' marker before the table, found none")
        return 1
    programs = {f"stage{d.name}" for d in (root / "stages").iterdir() if re.match(r"\d\d_\w+$", d.name)}
    rows, problems = {}, []
    for number, line in enumerate(lines[start + 1:], start + 2):
        if not line.startswith("|"):
            if rows:
                break
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        m = re.fullmatch(r"`([\w.-]+\.scene)`", cells[0])
        if not m:
            continue
        scene = m.group(1)
        if scene in rows:
            problems.append(f"{page}:{number}: expected one row per scene, found {scene} again")
        rows[scene] = number
        command = re.match(r"`(stage\d\d_\w+) (\S+)", cells[3]) if len(cells) == 5 else None
        if command is None:
            problems.append(f"{page}:{number}: expected five cells, the fourth a command `stageNN_name scenes/...`, "
                            f"found '{line}'")
            continue
        if command.group(1) not in programs:
            problems.append(f"{page}:{number}: expected a stage program, found {command.group(1)}; the programs "
                            f"are {', '.join(sorted(programs))}")
        if command.group(2) != f"scenes/{scene}":
            problems.append(f"{page}:{number}: expected the command to render scenes/{scene}, found {command.group(2)}")
    files = sorted(p.name for p in (root / "scenes").glob("*.scene"))
    problems += [f"{page}: expected a row for scenes/{name}, found none; say what it shows and which stage"
                 for name in files if name not in rows]
    problems += [f"{page}:{line}: the row names {name}, which is no file of scenes/"
                 for name, line in rows.items() if name not in files]
    for p in problems:
        print(p)
    print(f"{len(files)} scenes, {len(rows)} rows, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
