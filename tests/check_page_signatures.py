#!/usr/bin/env python3
"""check_page_signatures.py - the functions the stage pages quote have the headers' parameters.

    python3 tests/check_page_signatures.py [REPOSITORY]

The ctest test docs.signatures (label docs). It reads every page docs/stages/*.md and
finds the functions it quotes, in three forms:

- a declaration in a ```cpp block (`color blinn_phong(const material& m, ...);`, a
  `template <...>` line before it included): its return type and its parameter list,
  whitespace normalised, must equal those of a function of that name in include/rt;
- a heading `### `name(a, b, c = 0)`` and the first cell of a table row
  `| `name(a, b)` |`: the shorthand of the stage's functions. Written with types
  (`statement& line`), it is compared as a declaration's parameters; written with
  names only, it must list as many parameters as the header's function has (a
  parameter with a default value counts: `depth = 0` and then no `options` is the
  page falling behind the header).

A function is looked up by name among the definitions and declarations of every header
under include/rt (overloads: one of them must match). A name quoted in one of these forms
that include/rt does not define is reported (a page quoting a function that was renamed),
as is a page set where nothing was found to check; an object made with arguments in a
```cpp block (`const rt::accelerator world(scene);`) is listed as not checked. Each check prints one line; a mismatch
reads `page:line: name: the page says (...), include/rt/x.hpp:line says (...)`. Exit code 0
when everything matches. Python 3 standard library only.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional

IDENT = r"[A-Za-z_]\w*"


@dataclass
class Definition:
    path: str
    line: int
    returns: str
    params: List[str]


def strip_comments(text: str) -> str:
    """C++ comments replaced by spaces (newlines kept, so line numbers hold); strings left alone."""
    out: List[str] = []
    i, n = 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text[i] in "\"'":
            quote, j = text[i], i + 1
            while j < n and text[j] != quote:
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def normalise(text: str) -> str:
    """Whitespace collapsed, none beside punctuation: `const  vec3 &n` -> `const vec3&n`."""
    text = re.sub(r"\s+", " ", text.strip())
    return re.sub(r"\s*([&*,()<>=:{}\[\]])\s*", r"\1", text)


def split_params(text: str) -> List[str]:
    """The parameters of a parameter list, split at the commas outside <>, (), {}."""
    params, depth, current = [], 0, []
    for c in text:
        if c in "<({[":
            depth += 1
        elif c in ">)}]":
            depth -= 1
        if c == "," and depth == 0:
            params.append("".join(current))
            current = []
        else:
            current.append(c)
    last = "".join(current)
    if last.strip() or params:
        params.append(last)
    params = [normalise(p) for p in params]
    return [] if params in ([""], ["void"]) else params


def closing(text: str, open_at: int) -> int:
    """The index of the parenthesis that closes the one at open_at, or -1."""
    depth = 0
    for i in range(open_at, len(text)):
        if text[i] == "(":
            depth += 1
        elif text[i] == ")":
            depth -= 1
            if depth == 0:
                return i
    return -1


# a function's head at the start of a line: [template <...>] [inline|constexpr|static ...] type name(
HEAD = re.compile(r"^[ \t]*(?:template\s*<[^;{}]*?>\s*)?(?P<specifiers>(?:(?:inline|constexpr|static)\s+)*)"
                  r"(?P<returns>(?:const\s+)?[A-Za-z_][\w:]*(?:<[^;{}()]*?>)?(?:\s*[&*])?)\s+"
                  r"(?P<name>" + IDENT + r")\s*\(", re.M)
NOT_A_TYPE = {"return", "else", "new", "delete", "throw", "case", "goto", "using", "typedef", "operator"}


def definitions(root: Path) -> Dict[str, List[Definition]]:
    """Every function defined or declared at the start of a line in include/rt, by name."""
    found: Dict[str, List[Definition]] = {}
    for header in sorted((root / "include" / "rt").rglob("*.hpp")):
        text = strip_comments(header.read_text(encoding="utf-8"))
        for match in HEAD.finditer(text):
            returns = match.group("returns")
            if returns.split()[0] in NOT_A_TYPE:
                continue
            end = closing(text, match.end() - 1)
            if end < 0:
                continue
            after = text[end + 1:end + 40].lstrip()
            if not after.startswith(("{", ";", "const", "noexcept", "->")):
                continue  # a call or an initialisation, not a function's head
            found.setdefault(match.group("name"), []).append(
                Definition(str(header.relative_to(root)), text.count("\n", 0, match.start("name")) + 1,
                           normalise(returns), split_params(text[match.end():end])))
    return found


@dataclass
class Quote:
    page: str
    line: int
    name: str
    params: List[str]
    returns: Optional[str]  # a declaration's return type; None for a shorthand
    typed: bool             # the parameters carry their types


def cpp_declarations(page: str, text: str) -> List[Quote]:
    """The function declarations of the page's ```cpp blocks."""
    quotes = []
    for block in re.finditer(r"^```cpp[ \t]*\n(?P<body>.*?)^```", text, re.M | re.S):
        body = strip_comments(block.group("body"))
        first_line = text.count("\n", 0, block.start("body")) + 1
        for match in HEAD.finditer(body):
            returns = match.group("returns")
            if returns.split()[0] in NOT_A_TYPE:
                continue
            end = closing(body, match.end() - 1)
            if end < 0 or not body[end + 1:].lstrip().startswith((";", "{", "const")):
                continue
            params = split_params(body[match.end():end])
            quotes.append(Quote(page, first_line + body.count("\n", 0, match.start("name")), match.group("name"),
                                params, normalise(returns), typed(params)))
    return quotes


def typed(params: List[str]) -> bool:
    """Whether parameters carry their types (`const vec3&n`, `real t`), not names alone (`n`, `depth=0`)."""
    return any(re.search(r"[&*]|\w\s+\w", p.split("=")[0]) for p in params)


SHORTHAND = re.compile(r"`(?P<name>" + IDENT + r")\((?P<params>[^`]*)\)`")


def shorthands(page: str, text: str) -> List[Quote]:
    """`name(a, b)` in a ### heading or in the first cell of a table row."""
    quotes = []
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("###"):
            match = SHORTHAND.search(line)
        elif line.startswith("| `"):
            match = SHORTHAND.match(line, 2)
        else:
            continue
        if not match:
            continue
        params = split_params(match.group("params"))
        quotes.append(Quote(page, number, match.group("name"), params, None, typed(params)))
    return quotes


def param_names(params: List[str]) -> str:
    """A parameter list for a message, spaced as written: `(const vec3& n, int depth = 0)`."""
    shown = [re.sub(r"\s*=\s*", " = ", re.sub(r"([&*])(\w)", r"\1 \2", p)) for p in params]
    return "(" + ", ".join(shown) + ")"


def check(root: Path) -> int:
    known = definitions(root)
    pages = sorted((root / "docs" / "stages").glob("*.md"))
    quotes: List[Quote] = []
    for page in pages:
        rel = str(page.relative_to(root))
        text = page.read_text(encoding="utf-8")
        quotes += cpp_declarations(rel, text) + shorthands(rel, text)
    failures = 0
    checked = 0
    for quote in quotes:
        where = f"{quote.page}:{quote.line}: {quote.name}"
        if quote.returns is not None and quote.params and not quote.typed:
            print(f"{where}: not checked: an object made with arguments ({', '.join(quote.params)}), not a function")
            continue
        candidates = known.get(quote.name, [])
        if not candidates:
            print(f"{where}: the page quotes a function that no header under include/rt defines")
            failures += 1
            continue
        checked += 1
        if quote.typed:
            match = next((d for d in candidates if d.params == quote.params and
                          (quote.returns is None or d.returns == quote.returns)), None)
        else:
            match = next((d for d in candidates if len(d.params) == len(quote.params)), None)
        if match:
            count = len(quote.params)
            print(f"{where}: ok ({'declaration' if quote.returns else 'shorthand'}, "
                  f"{count} parameter{'' if count == 1 else 's'}, {match.path}:{match.line})")
            continue
        failures += 1
        said = (quote.returns + " " if quote.returns else "") + param_names(quote.params)
        for d in candidates:
            header = (d.returns + " " if quote.returns else "") + param_names(d.params)
            if quote.typed:
                print(f"{where}: the page says {said}, {d.path}:{d.line} says {header}")
            else:
                print(f"{where}: the page lists {len(quote.params)} parameters {said}, {d.path}:{d.line} has "
                      f"{len(d.params)} {header}")
    if checked == 0:
        print(f"check_page_signatures: found no quoted function to check in {len(pages)} pages under docs/stages")
        return 1
    print(f"check_page_signatures: {checked} quoted functions checked in {len(pages)} pages, {failures} wrong")
    return 1 if failures else 0


def main(argv: List[str]) -> int:
    root = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parent.parent
    if not (root / "docs" / "stages").is_dir() or not (root / "include" / "rt").is_dir():
        print(f"check_page_signatures: expected a repository with docs/stages and include/rt, found {root}")
        return 2
    return check(root)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
