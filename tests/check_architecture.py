#!/usr/bin/env python3
"""Holds include/rt to the layer table of docs/architecture.md.

Every header under include/rt belongs to exactly one group of the table, and
includes (with #include "...") only headers of the groups its row allows.
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
    group_of, allowed, problems = {}, {}, []
    for number, line in enumerate(lines[start + 1:], start + 2):
        if not line.startswith("|"):
            if allowed:
                break
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) != 3 or cells[0] in ("group", "") or set(cells[0]) <= {"-"}:
            continue
        group, headers, may = cells
        allowed[group] = set(may.split())
        for h in headers.split():
            if h in group_of:
                problems.append(f"{page}:{number}: expected each header in one group, found {h} in "
                                f"{group_of[h]} and {group}")
            group_of[h] = group
    for group, may in allowed.items():
        for g in may - set(allowed):
            problems.append(f"{page}: group {group} may include '{g}', which is no group of the table")
    headers = sorted(p for p in include.rglob("*.hpp"))
    for path in headers:
        name = path.relative_to(include).with_suffix("").as_posix()
        if name not in group_of:
            problems.append(f"{path}: expected a row of docs/architecture.md's layer table to list "
                            f"'{name}', found none; add it to the group of its concept")
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+)\.hpp"', line)
            if not m:
                continue
            target = (path.parent / (m.group(1) + ".hpp")).resolve().relative_to(include.resolve())
            target = target.with_suffix("").as_posix()
            if target not in group_of:
                continue  # reported above, as a header missing from the table
            mine, theirs = group_of[name], group_of[target]
            if theirs not in allowed[mine]:
                problems.append(f"{path}:{number}: a {mine} header includes {target}.hpp ({theirs}); "
                                f"expected only {', '.join(sorted(allowed[mine]))}: a header never reaches up "
                                f"(docs/architecture.md)")
    listed = set(group_of) - {p.relative_to(include).with_suffix("").as_posix() for p in headers}
    for h in sorted(listed):
        problems.append(f"{page}: the table lists '{h}', which is no header under include/rt")
    for p in problems:
        print(p)
    print(f"{len(headers)} headers in {len(allowed)} groups, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
