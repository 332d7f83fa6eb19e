#!/usr/bin/env python3
"""Holds rt's public names to the committed list, tests/public_names.txt.

Lists every name declared directly in namespace rt by the headers under
include/rt (the bvh fast path's inline namespaces count as rt: a user reaches
their names as rt::name; rt::detail and what it holds do not), and compares
that list with tests/public_names.txt. A name in the headers and not in the
list is a helper leaking into rt (move it into rt::detail), or new API (add it
to the list, deliberately); a name in the list and not in the headers is API
removed or renamed. And rt.hpp includes exactly the headers that declare public
names (bvh/bvh.hpp stands for the bvh/ folder's fast-path headers).
Usage: check_public_names.py REPO_ROOT [--print | --self-test]. Prints one line
per problem, exits 1; --print writes the names found, one a line, for a new
list; --self-test shows the check failing on a small tree with a leak.
"""
import pathlib
import re
import sys

KEYWORDS = {"inline", "constexpr", "static", "extern", "template", "typename", "const", "noexcept",
            "explicit", "virtual", "friend", "unsigned", "signed", "long", "short", "int", "char",
            "bool", "float", "double", "void", "auto", "volatile", "decltype", "sizeof", "return"}


def strip(text: str) -> str:
    """The code of a header without comments, string and character literals, or preprocessor lines."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            i = text.find("\n", i)
            i = n if i < 0 else i
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            out.append(" ")
            i = n if j < 0 else j + 2
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i)
            out.append('""')
            i = n if end < 0 else end + len(m.group(1)) + 2
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator, 1'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    lines, code = "".join(out).split("\n"), []
    skip = False
    for line in lines:
        if skip or line.lstrip().startswith("#"):
            skip = line.rstrip().endswith("\\")
            code.append("")
        else:
            code.append(line)
    return "\n".join(code)


def declared_name(statement: str):
    """The name a namespace-scope declaration declares, or None."""
    s = re.sub(r"\[\[.*?\]\]", " ", statement).strip()
    s = re.sub(r"\s+", " ", s)
    while s.startswith("template"):  # drop template<...>
        depth, k = 0, s.find("<")
        for k in range(k, len(s)):
            depth += {"<": 1, ">": -1}.get(s[k], 0)
            if depth == 0:
                break
        s = s[k + 1:].strip()
    if not s or s.startswith(("static_assert", "using namespace")):
        return None
    m = re.match(r"using (\w+)\s*=", s)
    if m:
        return m.group(1)
    if s.startswith("using "):
        m = re.match(r"using (?:typename )?[\w:]*::(\w+)$", s)
        return m.group(1) if m else None
    m = re.match(r"(?:typedef .*\b(\w+)$)", s)
    if m:
        return m.group(1)
    m = re.match(r"(?:enum(?: class| struct)?|struct|class|union)\s+(?:alignas\([^)]*\)\s*)?(\w+)", s)
    if m and "(" not in s.split(m.group(1), 1)[0]:
        return m.group(1)
    # A function: the name before the first '(' outside <...>; operators are not names of their own.
    depth = 0
    for k, ch in enumerate(s):
        if ch == "<":
            depth += 1
        elif ch == ">":
            depth -= 1
        elif ch == "(" and depth <= 0:
            head = s[:k].rstrip()
            if re.search(r"\boperator\s*\S*$", head) or head.endswith("operator"):
                return None
            m = re.search(r"(\w+)$", head)
            if m and m.group(1) not in KEYWORDS | {"decltype", "alignas"}:
                return m.group(1)
            break
        elif ch in "={":
            break
    m = re.match(r"(.*?)\s*(?:=|\{|\[|$)", s)
    m = re.search(r"(\w+)$", m.group(1)) if m else None
    return m.group(1) if m and m.group(1) not in KEYWORDS else None


def names_in(code: str):
    """Yields (name, line) for each declaration directly in rt (or an inline namespace of rt)."""
    stack = []  # one entry per open brace: 'rt', 'public' (transparent), 'hidden', or 'block'
    statement, start_line, line = [], None, 1
    i, n = 0, len(code)

    def public_scope():
        scopes = [s for s in stack if s != "block"]
        return bool(scopes) and len(scopes) == len(stack) and scopes[0] == "rt" and all(
            s in ("rt", "public") for s in scopes)

    while i < n:
        c = code[i]
        if c == "\n":
            line += 1
        if c == "{":
            text = "".join(statement).strip()
            m = re.search(r"(?:^|\s)(inline\s+|RT_\w+\s+)?namespace\s*([\w:]*)\s*$", text)
            if m and text.startswith(("namespace", "inline", "RT_")):
                name = m.group(2)
                if not stack and name == "rt":
                    stack.append("rt")
                elif name == "detail" or name.endswith("::detail") or "detail" in name.split("::"):
                    stack.append("hidden")
                elif m.group(1) or name.startswith("RT_") or name.startswith("bvh_"):
                    stack.append("public" if public_scope() else "hidden")
                else:
                    stack.append("hidden")
                statement, start_line = [], None
            else:
                if public_scope() and text:
                    name = declared_name(text)
                    if name:
                        yield name, start_line or line
                depth = 1  # skip the body
                j = i + 1
                while j < n and depth:
                    if code[j] == "{":
                        depth += 1
                    elif code[j] == "}":
                        depth -= 1
                    elif code[j] == "\n":
                        line += 1
                    j += 1
                i = j
                # a class/variable ends at ';' after the body; a function at the '}'
                rest = code[i:i + 200].lstrip()
                if rest.startswith(";"):
                    i = code.index(";", i) + 1
                statement, start_line = [], None
                continue
        elif c == "}":
            if stack:
                stack.pop()
            statement, start_line = [], None
        elif c == ";":
            text = "".join(statement).strip()
            if public_scope() and text:
                name = declared_name(text)
                if name:
                    yield name, start_line or line
            statement, start_line = [], None
        else:
            if start_line is None and not c.isspace():
                start_line = line
            statement.append(c)
        i += 1


def public_names(include: pathlib.Path) -> dict:
    found = {}
    for path in sorted(include.rglob("*.hpp")):
        code = strip(path.read_text(encoding="utf-8"))
        for name, line in names_in(code):
            found.setdefault(name, f"{path}:{line}")
    return found


def umbrella(include: pathlib.Path) -> list:
    """rt.hpp includes every header that declares public names (bvh/bvh.hpp for the rest of bvh/), and no other."""
    path = include / "rt.hpp"
    included = set(re.findall(r'^#include "([^"]+)"', path.read_text(encoding="utf-8"), re.M))
    public = set()
    for header in sorted(include.rglob("*.hpp")):
        if header.name != "rt.hpp" and any(True for _ in names_in(strip(header.read_text(encoding="utf-8")))):
            name = header.relative_to(include).as_posix()
            # the fast path's own headers are reached through bvh/bvh.hpp
            public.add("bvh/bvh.hpp" if name.startswith("bvh/") and name not in included else name)
    problems = [f"{path}: expected #include \"{h}\", which declares public names, found it missing; add it"
                for h in sorted(public - included)]
    problems += [f"{path}: includes \"{h}\", which declares no public name; expected only the public "
                 f"headers: remove it" for h in sorted(included - public)]
    return problems


def self_test() -> int:
    """The check fails on a leaked helper, a listed name gone and an umbrella that misses a header."""
    import contextlib
    import io
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        (root / "include" / "rt").mkdir(parents=True)
        (root / "tests").mkdir()
        (root / "include" / "rt" / "a.hpp").write_text(
            "namespace rt {\nstruct api {};\ninline int helper() { return 1; }\n"
            "namespace detail {\ninline int hidden() { return 2; }\n} // namespace detail\n} // namespace rt\n")
        (root / "include" / "rt" / "rt.hpp").write_text("#pragma once\n")
        (root / "tests" / "public_names.txt").write_text("# a comment\napi\ngone\n")
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            code = run(root, False)
    text = out.getvalue()
    wanted = ["rt::helper is public but not in tests/public_names.txt", "rt::gone is listed but no header",
              'expected #include "a.hpp"', "3 problem(s)"]
    missing = [w for w in wanted if w not in text] + (["rt::hidden not reported"] if "hidden" in text else [])
    if code != 1 or missing:
        print(f"self-test: expected exit 1 and {wanted}, found exit {code} and:\n{text}")
        return 1
    print("self-test: a leaked helper, a listed name gone and a header missing from rt.hpp are each reported")
    return 0


def main() -> int:
    if "--self-test" in sys.argv:
        return self_test()
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("--") else ".")
    return run(root, "--print" in sys.argv)


def run(root: pathlib.Path, print_names: bool) -> int:
    found = public_names(root / "include" / "rt")
    if print_names:
        print("\n".join(sorted(found)))
        return 0
    listing = root / "tests" / "public_names.txt"
    listed = {l.split("#")[0].strip() for l in listing.read_text(encoding="utf-8").splitlines()} - {""}
    problems = []
    for name in sorted(set(found) - listed):
        problems.append(f"{found[name]}: rt::{name} is public but not in tests/public_names.txt; expected "
                        f"only the listed API in namespace rt: move it into rt::detail if it is a helper, "
                        f"or add it to the list if users may rely on it")
    for name in sorted(listed - set(found)):
        problems.append(f"{listing}: rt::{name} is listed but no header under include/rt declares it in "
                        f"namespace rt; expected every listed name: restore it, or remove it from the list "
                        f"if the API changed deliberately")
    problems += umbrella(root / "include" / "rt")
    for p in problems:
        print(p)
    print(f"{len(found)} public names in include/rt, {len(listed)} listed; {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
