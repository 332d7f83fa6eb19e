#!/usr/bin/env python3
"""Holds the code to what docs/architecture.md, bvh/bvh.hpp and the README say of it.

- include/rt holds folders only, besides rt.hpp, and the layer table has one
  row per folder. A header's layer is its folder: it includes (with
  #include "...") only headers of its folder and of the folders its row allows.
- The teaching path of docs/architecture.md, and its stage table, name with
  its stage every header that holds an exercise region
  (RT_EXERCISE_BEGIN(stageNN: ...)), and no other.
- The folder map at the top of include/rt/bvh/bvh.hpp lists every file of
  include/rt/bvh, and only those.
- The README's "For developers" paragraph names every preset .ci/run runs,
  and .ci/run runs every preset the paragraph names.
Usage: check_architecture.py REPO_ROOT. Prints one line per problem, exits 1.
"""
import pathlib
import re
import sys


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    page = root / "docs" / "architecture.md"
    include = root / "include" / "rt"
    lines = page.read_text(encoding="utf-8").splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith("<!-- architecture:")), None)
    if start is None:
        print(f"{page}: expected the '<!-- architecture:' marker before the layer table, found none")
        return 1
    allowed, problems = {}, []
    for number, line in enumerate(lines[start + 1:], start + 2):
        if not line.startswith("|"):
            if allowed:
                break
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) != 3 or not cells[0].startswith("`"):
            continue
        group = cells[0].strip("`").rstrip("/")
        if group in allowed:
            problems.append(f"{page}:{number}: expected one row per folder, found `{group}/` twice")
        allowed[group] = set(cells[2].replace("`", "").replace("/", " ").split())
    for group, may in allowed.items():
        for g in may - set(allowed):
            problems.append(f"{page}: the row of `{group}/` may include '{g}', which has no row of the table")
    for entry in sorted(include.iterdir()):
        if entry.is_dir() and entry.name not in allowed:
            problems.append(f"{entry}: expected a row of docs/architecture.md's layer table for this folder, "
                            f"found none; add one saying what it holds and what it may include")
        elif entry.is_file() and entry.name != "rt.hpp":
            problems.append(f"{entry}: expected only folders and rt.hpp in include/rt, found a file; "
                            f"move it to the folder of its layer")
    for group in sorted(set(allowed) - {"rt.hpp"}):
        if not (include / group).is_dir():
            problems.append(f"{page}: the table has a row for `{group}/`, which is no folder of include/rt")

    def group_of(rel: pathlib.PurePath) -> str:
        return rel.parts[0] if len(rel.parts) > 1 else rel.name

    headers = sorted(p for p in include.rglob("*.hpp"))
    for path in headers:
        mine = group_of(path.relative_to(include))
        if mine not in allowed:
            continue  # reported above, as a folder missing from the table
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+\.hpp)"', line)
            if not m:
                continue
            target = (path.parent / m.group(1)).resolve()
            if not target.is_file():
                problems.append(f"{path}:{number}: includes {m.group(1)}, which is no file")
                continue
            rel = target.relative_to(include.resolve())
            theirs = group_of(rel)
            if theirs != mine and theirs not in allowed[mine]:
                problems.append(f"{path}:{number}: a {mine}/ header includes {rel.as_posix()} ({theirs}/); "
                                f"expected only {', '.join(sorted(allowed[mine]))}: a header never reaches up "
                                f"(docs/architecture.md)")
    problems += teaching_path(root) + bvh_map(root) + ci_claims(root)
    for p in problems:
        print(p)
    print(f"{len(headers)} headers in {len(allowed)} folders; the teaching path, the bvh map and the CI "
          f"claims checked; {len(problems)} problem(s)")
    return 1 if problems else 0


def teaching_path(root: pathlib.Path) -> list:
    """The teaching path's headers and stages against the exercise markers."""
    page = root / "docs" / "architecture.md"
    text = page.read_text(encoding="utf-8")
    m = re.search(r"^- \*\*The teaching path\*\*(.*?)(?=^- \*\*|^#)", text, re.S | re.M)
    if not m:
        return [f"{page}: expected a bullet '- **The teaching path**' listing the exercise headers, found none"]
    listed = {}
    pending = []
    for token in re.finditer(r"`([\w/]+\.hpp)`|\((\d\d)\)", m.group(1)):
        if token.group(1):
            pending.append(token.group(1))
        else:
            for header in pending:
                listed.setdefault(header, set()).add(int(token.group(2)))
            pending = []
    marked = {}
    include = root / "include" / "rt"
    for path in sorted(include.rglob("*.hpp")):
        for stage in re.findall(r"RT_EXERCISE_BEGIN\(stage(\d\d)", path.read_text(encoding="utf-8")):
            marked.setdefault(path.relative_to(include).as_posix(), set()).add(int(stage))
    problems = []
    for header, stages in sorted(marked.items()):
        if listed.get(header) != stages:
            problems.append(f"{page}: expected the teaching path to list `{header}` with stage(s) "
                            f"{', '.join(f'{s:02d}' for s in sorted(stages))} (its exercise markers), found "
                            + (f"stage(s) {', '.join(f'{s:02d}' for s in sorted(listed[header]))}" if header in listed
                               else "it missing"))
    table = re.search(r"^## Where a stage's files are\n(.*?)(?=^#)", text, re.S | re.M)
    if not table:
        problems.append(f"{page}: expected a section \"## Where a stage's files are\" with a row per stage, found none")
    else:
        rows = {}
        for line in table.group(1).splitlines():
            cells = [c.strip() for c in line.strip("|").split("|")]
            if line.startswith("|") and cells[0].isdigit():
                rows[int(cells[0])] = set(re.findall(r"`([\w/]+\.hpp)`", cells[1]))
        by_stage = {}
        for header, stages in marked.items():
            for s in stages:
                by_stage.setdefault(s, set()).add(header)
        for s in sorted(set(rows) | set(by_stage)):
            if rows.get(s) != by_stage.get(s):
                problems.append(f"{page}: expected the stage table's row {s:02d} to name "
                                f"{' '.join(sorted(by_stage.get(s, ()))) or 'no header'} (the exercise markers), "
                                f"found {' '.join(sorted(rows.get(s, ()))) or 'no row'}")
    for header in sorted(set(listed) - set(marked)):
        problems.append(f"{page}: the teaching path lists `{header}`, which holds no exercise region; "
                        f"move it to the robust and fast path or drop it")
    return problems


def bvh_map(root: pathlib.Path) -> list:
    """The folder map at the top of bvh/bvh.hpp against the folder."""
    path = root / "include" / "rt" / "bvh" / "bvh.hpp"
    lines = path.read_text(encoding="utf-8").splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith("// The folder,")), None)
    if start is None:
        return [f"{path}: expected the folder map ('// The folder, ...') at the top, found none"]
    mapped = []
    for line in lines[start + 1:]:
        m = re.match(r"//\s+(\w+\.hpp)\s", line + " ")
        if not m:
            break
        mapped.append(m.group(1))
    files = sorted(p.name for p in path.parent.glob("*.hpp"))
    problems = [f"{path}: expected the folder map to list {name}, a file of include/rt/bvh, found it missing"
                for name in files if name not in mapped]
    problems += [f"{path}: the folder map lists {name}, which is no file of include/rt/bvh"
                 for name in mapped if name not in files]
    return problems


def ci_claims(root: pathlib.Path) -> list:
    """The presets the README says CI runs against those .ci/run runs. A student kit
    (no tools/make_kit.py) has its own README and .ci/run (tools/kit/): nothing to check."""
    readme = root / "README.md"
    ci = root / ".ci" / "run"
    if not (root / "tools" / "make_kit.py").is_file():
        return []
    text = readme.read_text(encoding="utf-8")
    m = re.search(r"^## For developers\n(.*?)(?:\n\n|\Z)", text, re.S | re.M)
    if not m:
        return [f"{readme}: expected a '## For developers' section saying what CI runs, found none"]
    presets = {p["name"] for p in __import__("json").loads((root / "CMakePresets.json").read_text(encoding="utf-8"))
               .get("configurePresets", [])}
    claimed = set()
    for code in re.findall(r"`([^`]+)`", m.group(1)):
        claimed.update(re.findall(r"--preset\s+([\w-]+)", code))
        if code in presets:
            claimed.add(code)
    run = ci.read_text(encoding="utf-8")
    used = set(re.findall(r"^\s*cmake\b[^\n]*?--preset\s+([\w-]+)", run, re.M))
    problems = [f"{readme}: expected the 'For developers' paragraph to name the `{p}` preset, which .ci/run runs, "
                f"found it missing" for p in sorted(used - claimed)]
    problems += [f"{readme}: the 'For developers' paragraph says CI runs the `{p}` preset, which .ci/run does not run"
                 for p in sorted(claimed - used)]
    return problems


if __name__ == "__main__":
    sys.exit(main())
