#!/usr/bin/env python3
"""Measured figures live in docs/performance.md and its generated tables, nowhere else.

    python3 tests/check_figure_places.py ROOT        check ROOT's headers and README
    python3 tests/check_figure_places.py --self-test  the check finds what it must

A figure copied into a code comment or the README goes stale the day the
benchmark runs again, and two copies soon disagree. So every header under
include/ and the README, outside a block a script generates (between
`<!-- generated: ... -->` and `<!-- end generated -->`), may not hold a number
followed by `%`, `ms`, `Mrays` or `x faster`. A comment that needs a figure
names the experiment instead: (docs/performance.md, "The path picked at run time").
"""
import pathlib
import re
import sys

# 7%, 7-27%, +0.5%, 12 ms, 12ms, 4.56 Mrays/s, 3.69 Mrays, 2x faster, 1.5 x faster
NUMBER = r"\d(?:[\d.,]*\d)?"
FIGURE = re.compile(NUMBER + r"(?:\s?-\s?[+-]?" + NUMBER + r")?(?:%|\s?ms\b|\s?Mrays\b|\s?x faster\b)")
GENERATED_BEGIN = re.compile(r"<!--\s*generated\b")
GENERATED_END = re.compile(r"<!--\s*end generated\s*-->")
HINT = ('hint: measured figures live in docs/performance.md; name the experiment instead, '
        'as (docs/performance.md, "The path picked at run time")')


def figures_in(path: pathlib.Path, shown: str, markdown: bool) -> list:
    problems = []
    generated = False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if markdown and GENERATED_BEGIN.search(line):
            generated = True
        if not generated:
            for found in FIGURE.finditer(line):
                problems.append(f"{shown}:{number}:{found.start() + 1}: expected no measured figure outside "
                                f"docs/performance.md, found \"{found.group(0)}\"; {HINT}")
        if markdown and GENERATED_END.search(line):
            generated = False
    return problems


def check(root: pathlib.Path) -> list:
    problems = []
    for header in sorted((root / "include").rglob("*.hpp")):
        problems += figures_in(header, header.relative_to(root).as_posix(), markdown=False)
    readme = root / "README.md"
    if readme.exists():
        problems += figures_in(readme, "README.md", markdown=True)
    return problems


def self_test() -> int:
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        (root / "include" / "rt" / "core").mkdir(parents=True)
        (root / "include" / "rt" / "core" / "a.hpp").write_text(
            "// 8-wide nodes: shadow rays 7-27% faster\n"
            "int f(int i) { return i % 2; } // a remainder, not a figure\n"
            "// (docs/performance.md, \"Whole frames\")\n", encoding="utf-8")
        (root / "README.md").write_text(
            "builds in 63 ms\n<!-- generated: bench/x.py -->\n| 4.56 Mrays/s |\n<!-- end generated -->\n"
            "2x faster\n", encoding="utf-8")
        found = check(root)
        expected = ['include/rt/core/a.hpp:1:30: expected no measured figure outside docs/performance.md, '
                    'found "7-27%"', 'README.md:1:11:', 'README.md:5:1:']
        missing = [e for e in expected if not any(p.startswith(e) for p in found)]
        if missing or len(found) != len(expected):
            print("self-test failed: expected 3 figures (a header's, the README's outside the generated block), "
                  "found:\n  " + "\n  ".join(found), file=sys.stderr)
            return 1
    print("self-test: a header's figure and the README's outside a generated block are each reported")
    return 0


def main(argv: list) -> int:
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1])
    problems = check(root)
    for problem in problems:
        print(problem, file=sys.stderr)
    headers = sum(1 for _ in (root / "include").rglob("*.hpp"))
    print(f"{headers} headers and README.md: {len(problems)} measured figure(s) outside docs/performance.md")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
