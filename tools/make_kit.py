#!/usr/bin/env python3
"""make_kit.py - write a student kit of rt from the reference repository.

Every exercise region of the chosen stages, i.e. the lines between

    // RT_EXERCISE_BEGIN(stageNN: short title)
    ...
    // RT_EXERCISE_END

(see DEVELOPERS.md), is replaced by a body that throws rt::exercise_not_done
with the stage, the title and the stage's doc page, keeping the signature, the
markers, every comment outside the region, the hint comments inside it, and a
TODO(stage NN) line. Instructor-only material named in tools/kit_manifest.json
is left out of the kit.

    python3 tools/make_kit.py --from-stage 3 ../rt-kit-week3   # stages 03.. stripped, 01-02 given solved
    python3 tools/make_kit.py --all ../rt-kit
    python3 tools/make_kit.py --list          # the regions, by stage
    python3 tools/make_kit.py --check         # validate the markers only

A kit strips a stage and every later one: the earlier stages are handed out
solved, and the kit's last line says which answers it gives away. Stages are
discovered, never listed here: a stage exists when tests/stageNN_*.cpp exists;
its doc page is docs/stages/NN-*.md. Marker errors are printed as
"file:line:col: expected X, found Y; hint", one per line, and the exit code is 2.

Python 3 standard library only.
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import os
import posixpath
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterable, List, Optional, Sequence, Set, Tuple

TOOLS_DIR = Path(__file__).resolve().parent
DEFAULT_SOURCE = TOOLS_DIR.parent
MANIFEST_NAME = "tools/kit_manifest.json"

BEGIN_RE = re.compile(r"^RT_EXERCISE_BEGIN\((?P<inside>.*)\)$")
BEGIN_INSIDE_RE = re.compile(r"^stage(?P<stage>[0-9]{2}):\s*(?P<title>\S.*?)\s*"
                             r"(?:;\s*repeats\s+(?P<repeats>stage[0-9]{2}(?:\s*,\s*stage[0-9]{2})*)\s*)?$")
END_RE = re.compile(r"^RT_EXERCISE_END$")
HINT_RE = re.compile(r"^hint\b", re.IGNORECASE)
STAGE_TEST_RE = re.compile(r"^stage(?P<stage>[0-9]{2})_\w+\.cpp$")
STAGE_DOC_RE = re.compile(r"^(?P<stage>[0-9]{2})-[\w.-]+\.md$")
SOURCE_SUFFIXES = (".hpp", ".h", ".hh", ".hxx", ".ipp", ".inl", ".cpp", ".cc", ".cxx")

# Folders never copied, whatever the manifest says: build trees and VCS data.
ALWAYS_SKIPPED_DIRS = {".git", "__pycache__", ".cache", ".vscode", ".idea"}
BUILD_DIR_RE = re.compile(r"^(build|build-.*|cmake-build-.*|out)$")


class KitError(Exception):
    """One or more problems, each already a complete one-line message."""

    def __init__(self, messages: Sequence[str]):
        super().__init__("\n".join(messages))
        self.messages = list(messages)


# --------------------------------------------------------------------------
# Regions: finding and validating the markers
# --------------------------------------------------------------------------

@dataclass
class Region:
    path: str                 # posix path relative to the repository root
    stage: int
    title: str
    begin_line: int           # 1-based line of the BEGIN marker
    end_line: int             # 1-based line of the END marker
    indent: str               # indentation of the BEGIN marker
    function: str             # the function's name, for listings
    parameters: List[Tuple[str, bool]]  # (name, is_pack) of each named parameter
    hints: List[str] = field(default_factory=list)  # hint comment lines, stripped
    # Earlier stages whose answers this body repeats ("; repeats stage07" in the marker:
    # stage 09's ray color is stage 07's with glass added). A kit that strips one of
    # them strips this region too, so no finished answer sits beside a stripped one.
    repeats: List[int] = field(default_factory=list)

    def strips_with(self, stages: Set[int]) -> bool:
        return self.stage in stages or any(s in stages for s in self.repeats)

    def where(self) -> str:
        return f"{self.path}:{self.begin_line}"


def stage_label(stage: int) -> str:
    return f"{stage:02d}"


@dataclass
class _Context:
    kind: str                 # file, namespace, class, function, block, init
    open_line: int
    saved_statement: str = ""  # statement text before this brace (restored for init braces)
    signature: str = ""       # for functions: the declaration text before '{'
    code_seen: bool = False    # any code token inside this brace so far
    region: Optional[dict] = None  # open region directly in this function body
    region_closed_at: int = 0  # line of the END marker once the region closed


_KEYWORDS_BEFORE_PARENS = {"decltype", "alignas", "noexcept", "sizeof", "alignof",
                           "__attribute__", "__declspec", "requires", "static_assert",
                           "throw", "explicit"}
_TYPE_WORDS = {"int", "char", "short", "long", "unsigned", "signed", "float", "double",
               "bool", "void", "auto", "wchar_t", "char8_t", "char16_t", "char32_t",
               "const", "volatile", "struct", "class", "typename", "enum", "union"}


def _strip_template_prefix(text: str) -> str:
    """Removes leading `template <...>` clauses and [[attributes]]."""
    text = text.strip()
    while True:
        if text.startswith("[["):
            end = text.find("]]")
            if end < 0:
                return text
            text = text[end + 2:].strip()
            continue
        m = re.match(r"template\s*<", text)
        if not m:
            return text
        depth, i = 1, m.end()
        while i < len(text) and depth:
            if text[i] == "<":
                depth += 1
            elif text[i] == ">":
                depth -= 1
            i += 1
        text = text[i:].strip()


def _top_level_paren_groups(text: str) -> List[Tuple[int, int]]:
    """(start, end) indices of each top-level (...) group (end exclusive)."""
    groups, depth, start = [], 0, -1
    for i, ch in enumerate(text):
        if ch == "(":
            if depth == 0:
                start = i
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0 and start >= 0:
                groups.append((start, i + 1))
            depth = max(depth, 0)
    return groups


def _parameter_group(sig: str) -> Optional[Tuple[int, int]]:
    """The (...) group holding the parameters of the function declared by `sig`."""
    groups = _top_level_paren_groups(sig)
    for index, (start, end) in enumerate(groups):
        before = sig[:start].rstrip()
        m = re.search(r"([A-Za-z_]\w*)\s*(<[^()]*>)?$", before) or re.search(r"(operator\s*\S+)$", before)
        if not m:
            continue
        word = m.group(1)
        if word in _KEYWORDS_BEFORE_PARENS:
            continue
        if word == "operator" and sig[start:end] == "()" and index + 1 < len(groups):
            return groups[index + 1]  # operator()(...)
        return (start, end)
    return None


def _split_top_level(text: str, separator: str) -> List[str]:
    parts, depth, current = [], 0, []
    for ch in text:
        if ch in "(<[{":
            depth += 1
        elif ch in ")>]}":
            depth = max(depth - 1, 0)
        if ch == separator and depth == 0:
            parts.append("".join(current))
            current = []
        else:
            current.append(ch)
    parts.append("".join(current))
    return parts


def parse_parameters(sig: str) -> List[Tuple[str, bool]]:
    """Names of the named parameters of the function whose declaration is `sig`,
    each with True when it is a parameter pack."""
    group = _parameter_group(sig)
    if group is None:
        return []
    inside = sig[group[0] + 1:group[1] - 1].strip()
    if inside in ("", "void"):
        return []
    names = []
    for part in _split_top_level(inside, ","):
        part = part.strip()
        # drop a default argument: the first '=' at top level that is not part of ==, <=, >=, !=
        pieces = re.split(r"(?<![=!<>])=(?!=)", part, maxsplit=1)
        declarator = pieces[0].strip()
        if not declarator or declarator == "...":
            continue
        inner = re.search(r"\(\s*[*&]+\s*([A-Za-z_]\w*)\s*\)", declarator)  # void (*fn)(int), T (&a)[3]
        if inner:
            names.append((inner.group(1), False))
            continue
        declarator = re.sub(r"(\s*\[[^\]]*\])+$", "", declarator)  # int a[3]
        m = re.search(r"([A-Za-z_]\w*)$", declarator)
        if not m:
            continue  # ends with *, &, >: unnamed
        name = m.group(1)
        before = declarator[:m.start()].rstrip()
        if not before or before.endswith("::") or name in _TYPE_WORDS:
            continue  # `sphere`, `std::size_t`, `unsigned int`: a type without a name
        words = re.findall(r"[A-Za-z_]\w*", before)
        if all(w in ("const", "volatile", "struct", "class", "enum", "union", "typename") for w in words) \
                and not re.search(r"[*&>.]", before):
            continue  # `const sphere`: still only a type
        names.append((name, before.endswith("...")))
    return names


def _function_name(sig: str) -> str:
    group = _parameter_group(sig)
    if group is None:
        return "?"
    before = sig[:group[0]].rstrip()
    m = re.search(r"(operator\s*\S+|~?[A-Za-z_][\w:]*)\s*(<[^()]*>)?$", before)
    return m.group(1) if m else "?"


def _classify_brace(statement: str, parent: _Context) -> str:
    """What the '{' that ends `statement` opens, given the enclosing context."""
    if parent.kind not in ("file", "namespace", "class"):
        return "block"
    depth = 0
    for ch in statement:
        depth += ch == "("
        depth -= ch == ")"
    if depth > 0:
        return "init"  # a brace inside parentheses: f(T{})
    text = _strip_template_prefix(statement)
    if re.match(r"(inline\s+)?namespace\b", text) or re.match(r'extern\s*""', text):
        return "namespace"
    if re.match(r"(typedef\s+)?(class|struct|union|enum)\b", text):
        return "class"
    group = _parameter_group(text)
    if group is None:
        return "init"
    head = text[:group[0]]
    if re.search(r"(?<![=!<>+\-*/%&|^])=(?!=)", head) and not re.search(r"\boperator\b", head):
        return "init"  # auto x = f(1) + T{...}
    tail = text[group[1]:].strip()
    if tail.startswith(":") and not tail.startswith("::"):
        # constructor initializer list: the body follows a ')' or '}', a member's
        # brace initializer follows its name
        return "function" if re.search(r"[)}]\s*$", tail) else "init"
    return "function"


def scan_file(path: str, text: str, known_stages: Set[int], errors: List[str]) -> List[Region]:
    """Finds the regions of one file, appending marker errors to `errors`."""
    regions: List[Region] = []
    stack: List[_Context] = [_Context("file", 0)]
    statement: List[str] = []
    line = 1
    i, n = 0, len(text)
    line_start = 0
    rejected = {"begin": False}  # the last BEGIN was refused: its END is not reported again

    def err(at_line: int, column: int, expected: str, found: str, hint: str = "") -> None:
        message = f"{path}:{at_line}:{column}: expected {expected}, found {found}"
        if hint:
            message += f"; {hint}"
        errors.append(message)

    def mark_code() -> None:
        top = stack[-1]
        top.code_seen = True
        for ctx in reversed(stack):
            if ctx.region is not None:
                ctx.region["hint"]["active"] = False  # a hint runs up to the next line of code
                break
        # code after a closed region, in the function that holds it
        for ctx in reversed(stack):
            if ctx.kind == "function":
                if ctx.region_closed_at and ctx.region_closed_at > 0:
                    err(line, i - line_start + 1, "only the closing brace after RT_EXERCISE_END",
                        "more code in the function body",
                        f"the region (END at line {ctx.region_closed_at}) must be the whole body")
                    ctx.region_closed_at = -1  # report once
                break

    def handle_comment(comment: str, column: int, full_line: bool) -> None:
        body = comment.strip()
        top = stack[-1]
        function = next((c for c in reversed(stack) if c.kind == "function"), None)
        open_region = function.region if function else None
        if "RT_EXERCISE" not in body:
            if open_region is not None and full_line:
                hint = open_region["hint"]
                if HINT_RE.match(body):
                    hint["active"] = True
                elif not comment.startswith("  "):
                    hint["active"] = False  # a continuation line is indented further
                if hint["active"]:
                    open_region["hints"].append(comment.rstrip())
            return
        if not full_line:
            err(line, column, "an exercise marker alone on its line", "code before it",
                "put // RT_EXERCISE_BEGIN(...) and // RT_EXERCISE_END on lines of their own")
            return
        begin = BEGIN_RE.match(body)
        end = END_RE.match(body)
        if begin:
            inside = BEGIN_INSIDE_RE.match(begin.group("inside"))
            rejected["begin"] = True
            if not inside:
                err(line, column, '"RT_EXERCISE_BEGIN(stageNN: short title)"', f'"{body}"',
                    "two digits after stage, a colon, then the title")
                return
            stage = int(inside.group("stage"))
            repeats = [int(x) for x in re.findall(r"stage([0-9]{2})", inside.group("repeats") or "")]
            for earlier in repeats:
                if earlier >= stage or earlier not in known_stages:
                    err(line, column, f"an earlier stage with a test suite after 'repeats' (before {stage:02d})",
                        f"stage{earlier:02d}", "name the stages whose answers this body repeats")
            for ctx in stack:
                if ctx.kind == "function" and ctx.region is not None:
                    err(line, column, f"RT_EXERCISE_END of the region opened at line {ctx.region['line']}",
                        "another RT_EXERCISE_BEGIN", "regions do not nest: close the first one")
                    return
            if top.kind != "function":
                where = {"file": "file scope", "namespace": "a namespace", "class": "a class body",
                         "block": "a block inside a function", "init": "an initializer"}[top.kind]
                err(line, column, "RT_EXERCISE_BEGIN directly inside a function body", f"it in {where}",
                    "a region is a whole function body: markers on their own lines just inside its braces")
                return
            if top.region_closed_at:
                err(line, column, "one region per function body", "a second RT_EXERCISE_BEGIN",
                    f"this function's region ended at line {abs(top.region_closed_at)}")
                top.region_closed_at = -abs(top.region_closed_at)  # no more reports for this body
                return
            if top.code_seen:
                err(line, column, "RT_EXERCISE_BEGIN first in the function body", "code before it",
                    "a region is the whole body: move the code inside the region")
                return
            rejected["begin"] = False
            if stage not in known_stages:
                err(line, column, "a stage that has a test suite tests/stageNN_*.cpp",
                    f"stage {stage:02d}, which has none",
                    f"add tests/stage{stage:02d}_<name>.cpp or correct the stage number")
            sig = top.signature
            if re.search(r"\bnoexcept\b(?!\s*\(\s*false\s*\))", sig[(_parameter_group(sig) or (0, 0))[1]:]):
                err(top.open_line, 1, "an exercise function that may throw", "noexcept",
                    "the kit's body throws rt::exercise_not_done: remove noexcept")
            if re.search(r"\b(constexpr|consteval)\b", _strip_template_prefix(sig)):
                err(top.open_line, 1, "an exercise function that is not constexpr", "constexpr",
                    "the kit's body throws rt::exercise_not_done: remove constexpr")
            top.region = {"line": line, "column": column, "stage": stage,
                          "title": inside.group("title"), "repeats": repeats, "indent": text[line_start:line_start + column - 1],
                          "hints": [], "hint": {"active": False}}
            return
        if end:
            function = stack[-1] if stack[-1].kind == "function" else None
            if function is None or function.region is None:
                owner = next((c for c in reversed(stack) if c.kind == "function" and c.region), None)
                if owner is not None:
                    err(line, column, "RT_EXERCISE_END in the function body where its region began "
                        f"(line {owner.region['line']})", "it inside a nested block",
                        "put the END marker just before the function's closing brace")
                elif not rejected["begin"]:
                    err(line, column, "RT_EXERCISE_END after an RT_EXERCISE_BEGIN", "no open region",
                        "add the BEGIN marker or remove this one")
                rejected["begin"] = False
                return
            r = function.region
            sig = function.signature
            regions.append(Region(path=path, stage=r["stage"], title=r["title"], begin_line=r["line"],
                                  end_line=line, indent=r["indent"], function=_function_name(sig),
                                  parameters=parse_parameters(sig), hints=r["hints"],
                                  repeats=r["repeats"]))
            function.region = None
            function.region_closed_at = line
            return
        err(line, column, '"RT_EXERCISE_BEGIN(stageNN: title)" or "RT_EXERCISE_END"', f'"{body}"',
            "check the spelling of the marker")

    while i < n:
        ch = text[i]
        if ch == "\n":
            line += 1
            i += 1
            line_start = i
            statement.append(" ")
            continue
        if ch in " \t\r\f\v":
            statement.append(" ")
            i += 1
            continue
        column = i - line_start + 1
        # preprocessor directive: skip to the end of the (continued) line
        if ch == "#" and text[line_start:i].strip() == "":
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    line += 1
                    i += 2
                    line_start = i
                    continue
                if text.startswith("//", i):
                    break
                if text.startswith("/*", i):
                    close = text.find("*/", i + 2)
                    close = n if close < 0 else close + 2
                    line += text.count("\n", i, close)
                    if "\n" in text[i:close]:
                        line_start = text.rfind("\n", i, close) + 1
                    i = close
                    continue
                i += 1
            continue
        if text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            full_line = text[line_start:i].strip() == ""
            handle_comment(text[i + 2:end], column, full_line)
            i = end
            continue
        if text.startswith("/*", i):
            close = text.find("*/", i + 2)
            close = n if close < 0 else close + 2
            if "RT_EXERCISE" in text[i:close]:
                err(line, column, "exercise markers in // line comments", "one in a /* */ comment",
                    "write // RT_EXERCISE_BEGIN(...) on a line of its own")
            newlines = text.count("\n", i, close)
            if newlines:
                line += newlines
                line_start = text.rfind("\n", i, close) + 1
            i = close
            statement.append(" ")
            continue
        if ch == '"':
            mark_code()
            raw = bool(statement) and re.fullmatch(r"(u8|u|U|L)?R", statement[-1]) is not None
            if raw:
                open_paren = text.find("(", i + 1)
                delimiter = text[i + 1:open_paren]
                closing = ")" + delimiter + '"'
                close = text.find(closing, open_paren + 1)
                close = n if close < 0 else close + len(closing)
            else:
                j = i + 1
                while j < n and text[j] != '"' and text[j] != "\n":
                    j += 2 if text[j] == "\\" else 1
                close = min(j + 1, n)
            newlines = text.count("\n", i, close)
            if newlines:
                line += newlines
                line_start = text.rfind("\n", i, close) + 1
            statement.append('""')
            i = close
            continue
        if ch == "'":
            mark_code()
            j = i + 1
            while j < n and text[j] != "'" and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            statement.append("' '")
            i = min(j + 1, n)
            continue
        if ch.isdigit() or (ch == "." and i + 1 < n and text[i + 1].isdigit()):
            j = i + 1
            while j < n and (text[j].isalnum() or text[j] in "_.'"):  # 1'000, 0x1p-3f, 1.5e3
                j += 1
            mark_code()
            statement.append(text[i:j])
            i = j
            continue
        if ch.isalpha() or ch == "_":
            j = i + 1
            while j < n and (text[j].isalnum() or text[j] == "_"):
                j += 1
            mark_code()
            statement.append(text[i:j])
            i = j
            continue
        if ch == "{":
            parent = stack[-1]
            mark_code()
            stmt_text = "".join(statement)
            kind = _classify_brace(stmt_text, parent)
            ctx = _Context(kind, line, saved_statement=stmt_text)
            if kind == "function":
                ctx.signature = _strip_template_prefix(stmt_text)
            stack.append(ctx)
            statement = []
            i += 1
            continue
        if ch == "}":
            if len(stack) == 1:
                err(line, column, "a '{' before this '}'", "an unmatched '}'", "check the braces")
                i += 1
                continue
            closing = stack.pop()
            if closing.kind == "function" and closing.region is not None:
                err(closing.region["line"], closing.region["column"],
                    f"RT_EXERCISE_END before the function's closing brace (line {line})", "none",
                    "add // RT_EXERCISE_END just before the closing brace")
            if closing.kind in ("init",):
                statement = [closing.saved_statement, "{}"]
                mark_code()
            else:
                mark_code()
                statement = []
            i += 1
            continue
        if ch == ";":
            mark_code()
            so_far = "".join(statement)
            statement = [so_far, ";"] if so_far.count("(") > so_far.count(")") else []
            i += 1
            continue
        mark_code()
        statement.append(ch)
        i += 1

    for ctx in stack[1:]:
        if ctx.kind == "function" and ctx.region is not None:
            err(ctx.region["line"], ctx.region["column"], "RT_EXERCISE_END before the end of the file",
                "none", "add // RT_EXERCISE_END before the function's closing brace")
    return regions


# --------------------------------------------------------------------------
# The repository: stages, doc pages, files, manifest
# --------------------------------------------------------------------------

def known_stages(root: Path) -> Dict[int, List[str]]:
    """Stage number -> its test files tests/stageNN_*.cpp (relative paths)."""
    stages: Dict[int, List[str]] = {}
    tests = root / "tests"
    if tests.is_dir():
        for entry in sorted(tests.iterdir()):
            m = STAGE_TEST_RE.match(entry.name)
            if m and entry.is_file():
                stages.setdefault(int(m.group("stage")), []).append(f"tests/{entry.name}")
    return stages


def stage_doc(root: Path, stage: int) -> Optional[str]:
    """docs/stages/NN-<name>.md, or None when the stage has no page yet."""
    docs = root / "docs" / "stages"
    if docs.is_dir():
        for entry in sorted(docs.iterdir()):
            m = STAGE_DOC_RE.match(entry.name)
            # NN-going-further.md is the page after the lesson, never the lesson
            if m and int(m.group("stage")) == stage and not entry.name.endswith("-going-further.md"):
                return f"docs/stages/{entry.name}"
    return None


def load_manifest(root: Path) -> dict:
    path = root / MANIFEST_NAME
    manifest = {"exercise_roots": ["include", "stages"], "instructor_only": []}
    if path.is_file():
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except json.JSONDecodeError as e:
            raise KitError([f"{MANIFEST_NAME}:{e.lineno}:{e.colno}: expected JSON, found {e.msg}"])
        for key in manifest:
            if key in data:
                if not isinstance(data[key], list) or not all(isinstance(s, str) for s in data[key]):
                    raise KitError([f"{MANIFEST_NAME}:1:1: expected \"{key}\": a list of strings, "
                                    f"found {json.dumps(data[key])}"])
                manifest[key] = data[key]
    return manifest


def is_instructor_only(rel: str, patterns: Iterable[str]) -> bool:
    for pattern in patterns:
        if pattern.endswith("/"):
            if rel.startswith(pattern) or fnmatch.fnmatchcase(rel.split("/")[0] + "/", pattern):
                return True
            # a folder pattern with wildcards, e.g. tests/*/hidden/
            parts = rel.split("/")
            for k in range(1, len(parts)):
                if fnmatch.fnmatchcase("/".join(parts[:k]) + "/", pattern):
                    return True
        elif fnmatch.fnmatchcase(rel, pattern):
            return True
    return False


def repository_files(root: Path) -> List[str]:
    """The files of the repository: git's tracked and untracked-but-not-ignored
    files when `root` is a git work tree, else every file outside build folders."""
    try:
        out = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--cached", "--others",
                              "--exclude-standard"], capture_output=True, check=True)
        if (root / ".git").exists():
            files = sorted({f for f in out.stdout.decode("utf-8").split("\0") if f})
            return [f for f in files if (root / f).is_file() and not _in_skipped_dir(f)]
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in ALWAYS_SKIPPED_DIRS
                             and not BUILD_DIR_RE.match(d) and not d.startswith("."))
        for name in sorted(filenames):
            rel = Path(dirpath, name).relative_to(root).as_posix()
            files.append(rel)
    return files


def _in_skipped_dir(rel: str) -> bool:
    parts = rel.split("/")[:-1]
    return any(p in ALWAYS_SKIPPED_DIRS or BUILD_DIR_RE.match(p) for p in parts)


def exercise_files(files: Iterable[str], manifest: dict) -> List[str]:
    roots = [r.rstrip("/") + "/" for r in manifest["exercise_roots"]]
    return [f for f in files if f.endswith(SOURCE_SUFFIXES) and any(f.startswith(r) for r in roots)
            and not is_instructor_only(f, manifest["instructor_only"])]


def scan_repository(root: Path, files: Optional[List[str]] = None) -> List[Region]:
    """Every region of the repository; raises KitError listing every marker error."""
    manifest = load_manifest(root)
    files = repository_files(root) if files is None else files
    stages = set(known_stages(root))
    errors: List[str] = []
    regions: List[Region] = []
    for rel in exercise_files(files, manifest):
        try:
            text = (root / rel).read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        regions.extend(scan_file(rel, text, stages, errors))
    if errors:
        raise KitError(errors)
    return regions


# --------------------------------------------------------------------------
# Stripping
# --------------------------------------------------------------------------

def cxx_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def not_done_message(region: Region, doc: Optional[str]) -> str:
    page = doc if doc else "docs/student-guide.md"
    return f"stage {stage_label(region.stage)}: {region.title}: see {page}"


def stripped_body(region: Region, doc: Optional[str]) -> List[str]:
    """The lines that replace the region's body (between the kept markers)."""
    ind = region.indent
    page = doc if doc else "docs/student-guide.md"
    lines = [f"{ind}// TODO(stage {stage_label(region.stage)}): {region.title}; see {page}."]
    lines += [f"{ind}//{hint}" for hint in region.hints]
    for name, pack in region.parameters:
        lines.append(f"{ind}((void){name}, ...);" if pack else f"{ind}(void){name};")
    lines.append(f"{ind}throw rt::exercise_not_done({cxx_string(not_done_message(region, doc))});")
    return lines


def switchable_body(region: Region, doc: Optional[str], body: List[str]) -> List[str]:
    """check_kit's switchable kit: the region's own body, after a test that throws its
    not-done message when RT_KIT_STRIP names its stage (or a stage it repeats)."""
    ind = region.indent
    stages = ", ".join(str(s) for s in [region.stage] + list(region.repeats))
    lines = [f"{ind}if (rt::detail::kit_check_strips({{{stages}}})) {{"]
    for name, pack in region.parameters:
        lines.append(f"{ind}    ((void){name}, ...);" if pack else f"{ind}    (void){name};")
    lines.append(f"{ind}    throw rt::exercise_not_done({cxx_string(not_done_message(region, doc))});")
    lines.append(f"{ind}}}")
    return lines + body


# Appended to the switchable kit's include/rt/core/error.hpp (check_kit only, never a
# student's kit): everything after `#pragma once` in tools/kit/kit_check_switch.hpp.
KIT_CHECK_SWITCH_FILE = TOOLS_DIR / "kit" / "kit_check_switch.hpp"
KIT_CHECK_SWITCH = KIT_CHECK_SWITCH_FILE.read_text(encoding="utf-8").split("#pragma once\n", 1)[1]


def switchable_text(rel: str, text: str, regions: List[Region], doc_of: Dict[int, Optional[str]]) -> str:
    """`text` with each of `regions` (all of this file) made switchable (switchable_body)."""
    if not regions:
        return text
    lines = text.split("\n")
    for region in sorted(regions, key=lambda r: r.begin_line, reverse=True):
        body = lines[region.begin_line:region.end_line - 1]
        lines[region.begin_line:region.end_line - 1] = switchable_body(region, doc_of.get(region.stage), body)
    text = "\n".join(lines)
    if not re.search(r'^\s*#\s*include\s*[<"]([\w./]*/)?(rt/)?error\.hpp[>"]', text, re.MULTILINE):
        text = _with_error_include(rel, text)
    return text


def switchable_plan(root: Path) -> KitPlan:
    """A kit with every region solved but switchable at run time (see switchable_body):
    one build stands for every per-stage kit in check_kit."""
    plan = plan_kit(root, set())
    doc_of = {s: stage_doc(root, s) for s in known_stages(root)}
    by_file: Dict[str, List[Region]] = {}
    for r in plan.solved:
        by_file.setdefault(r.path, []).append(r)
    for rel, file_regions in by_file.items():
        plan.contents[rel] = switchable_text(rel, (root / rel).read_text(encoding="utf-8"), file_regions, doc_of)
    error_hpp = "include/rt/core/error.hpp"
    plan.contents[error_hpp] = plan.contents.get(error_hpp, (root / error_hpp).read_text(encoding="utf-8")) + \
        KIT_CHECK_SWITCH
    return plan


def _error_header_include(rel: str) -> str:
    """How a file at `rel` includes rt/core/error.hpp: by a relative path from inside
    include/rt, as the headers include each other; by <rt/...> from anywhere else."""
    if rel.startswith("include/rt/"):
        path = posixpath.relpath("include/rt/core/error.hpp", posixpath.dirname(rel))
        return f'#include "{path}" // rt::exercise_not_done (student kit)'
    return "#include <rt/core/error.hpp> // rt::exercise_not_done (student kit)"


def strip_text(rel: str, text: str, regions: List[Region], doc_of: Dict[int, Optional[str]]) -> str:
    """`text` with the bodies of `regions` (all of this file) replaced."""
    if not regions:
        return text
    lines = text.split("\n")
    for region in sorted(regions, key=lambda r: r.begin_line, reverse=True):
        body = stripped_body(region, doc_of.get(region.stage))
        lines[region.begin_line:region.end_line - 1] = body
    stripped = "\n".join(lines)
    if not re.search(r'^\s*#\s*include\s*[<"]([\w./]*/)?(rt/)?error\.hpp[>"]', stripped, re.MULTILINE):
        stripped = _with_error_include(rel, stripped)
    return stripped


def _with_error_include(rel: str, stripped: str) -> str:
    """`stripped` with rt/core/error.hpp included after the last #include of its opening block."""
    out = stripped.split("\n")
    at, in_comment = 0, False
    for k, l in enumerate(out):  # after the last #include of the file's opening block
        bare = l.strip()
        if in_comment:
            in_comment = "*/" not in bare
            continue
        if bare.startswith("/*"):
            in_comment = "*/" not in bare
            continue
        if re.match(r"#\s*(include|pragma\s+once)\b", bare):
            at = k + 1
        elif bare and not bare.startswith("//") and not bare.startswith("#"):
            break
    out.insert(at, _error_header_include(rel))
    stripped = "\n".join(out)
    return stripped


def select_stages(all_stages: Iterable[int], from_stage: Optional[int], strip_all: bool) -> Set[int]:
    """The stages a kit strips: every one (--all), or stage `from_stage` and every later
    one (--from-stage). A stage beyond the last would strip nothing and is refused."""
    stages = set(all_stages)
    if strip_all:
        return stages
    if from_stage is not None:
        if stages and from_stage > max(stages):
            raise KitError([f"--from-stage {from_stage}: expected a stage up to {stage_label(max(stages))}, "
                            f"the last with tests (tests/stageNN_*.cpp), found {stage_label(from_stage)}; "
                            f"a kit from it would strip nothing and hand out every answer"])
        return {s for s in stages if s >= from_stage}
    return set()


@dataclass
class KitPlan:
    files: List[str]                # files copied into the kit
    left_out: List[str]             # instructor-only files left out
    stripped: List[Region]          # regions replaced
    solved: List[Region]            # regions handed out solved
    contents: Dict[str, str]        # rel -> new text, for files with stripped regions
    missing_docs: List[int]         # stripped stages without a doc page


# A kit's file -> the instructor-only file that replaces it. In the replacement,
# KIT_STAGES_PLACEHOLDER becomes the stages the kit strips ("03 04 05"): the
# kit's CI script (tools/kit/ci-run) runs their tests, not the reference's CI.
KIT_REPLACEMENTS = {"README.md": "tools/kit/README.md", "DEVELOPERS.md": "tools/kit/DEVELOPERS.md",
                    ".ci/run": "tools/kit/ci-run"}
KIT_STAGES_PLACEHOLDER = "@RT_KIT_STAGES@"


def plan_kit(root: Path, stages_to_strip: Set[int], regions: Optional[List[Region]] = None) -> KitPlan:
    """The kit of `root` that strips `stages_to_strip`; `regions`: scan_repository(root)
    when the caller has it already (check_kit plans every kit from one scan)."""
    files = repository_files(root)
    manifest = load_manifest(root)
    regions = scan_repository(root, files) if regions is None else regions
    stages = known_stages(root)
    unknown = sorted(s for s in stages_to_strip if s not in stages)
    if unknown:
        raise KitError([f"expected a stage with tests (tests/stageNN_*.cpp: "
                        f"{', '.join(stage_label(s) for s in sorted(stages)) or 'none'}), "
                        f"found stage {stage_label(s)}; choose one of those" for s in unknown])
    doc_of = {s: stage_doc(root, s) for s in stages}
    stripped = [r for r in regions if r.strips_with(stages_to_strip)]
    solved = [r for r in regions if not r.strips_with(stages_to_strip)]
    kept, left_out = [], []
    for rel in files:
        (left_out if is_instructor_only(rel, manifest["instructor_only"]) else kept).append(rel)
    contents = {}
    by_file: Dict[str, List[Region]] = {}
    for r in stripped:
        by_file.setdefault(r.path, []).append(r)
    for rel, file_regions in by_file.items():
        text = (root / rel).read_text(encoding="utf-8")
        contents[rel] = strip_text(rel, text, file_regions, doc_of)
    # The kit's README, DEVELOPERS.md and CI script speak to students: the files
    # of tools/kit/ (instructor-only) replace the repository's, which describe
    # the reference, the instructor's tools and files a kit leaves out.
    for rel, replacement_rel in KIT_REPLACEMENTS.items():
        replacement = root / replacement_rel
        if replacement.is_file() and rel in kept:
            text = replacement.read_text(encoding="utf-8")
            contents[rel] = text.replace(KIT_STAGES_PLACEHOLDER, " ".join(
                stage_label(s) for s in sorted({r.stage for r in stripped})))
    missing = sorted({r.stage for r in stripped if doc_of.get(r.stage) is None})
    return KitPlan(kept, left_out, stripped, solved, contents, missing)


def write_tree(root: Path, plan: KitPlan, target: Path) -> None:
    """Writes the kit into the new folder `target`."""
    for rel in plan.files:
        destination = target / rel
        destination.parent.mkdir(parents=True, exist_ok=True)
        if rel in plan.contents:
            destination.write_text(plan.contents[rel], encoding="utf-8")
            shutil.copymode(root / rel, destination)
        else:
            shutil.copy2(root / rel, destination)


def write_kit(root: Path, plan: KitPlan, target: Path, force: bool = False) -> None:
    """Writes the kit atomically: into a sibling temporary folder, then renamed
    into place, so an interrupted run never leaves half a kit at `target`."""
    target = target.resolve()
    root = root.resolve()
    if target == root or root in target.parents and not _in_skipped_dir(target.relative_to(root).as_posix() + "/x"):
        raise KitError([f"{target}: expected a folder outside the repository (or inside a build folder), "
                        f"found one inside it; choose another target"])
    if target.exists() and not force and any(target.iterdir()):
        raise KitError([f"{target}: expected a new or empty folder, found one with files; "
                        f"pass --force to replace it"])
    target.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=target.name + ".tmp-", dir=target.parent))
    try:
        write_tree(root, plan, staging)
        if target.exists():
            old = Path(tempfile.mkdtemp(prefix=target.name + ".old-", dir=target.parent))
            os.rename(target, old / "kit")
            os.rename(staging, target)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.rename(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise


def sync_kit(root: Path, plan: KitPlan, target: Path) -> int:
    """Updates `target` in place to the kit: rewrites only files whose content
    differs and removes files not in the kit, so an existing build folder there
    rebuilds only what changed. Returns the number of files written."""
    target.mkdir(parents=True, exist_ok=True)
    wanted = set(plan.files)
    written = 0
    for rel in plan.files:
        destination = target / rel
        new = plan.contents[rel].encode("utf-8") if rel in plan.contents else (root / rel).read_bytes()
        if destination.is_file() and destination.read_bytes() == new:
            continue
        destination.parent.mkdir(parents=True, exist_ok=True)
        tmp = destination.with_name(destination.name + ".tmp-kit")
        tmp.write_bytes(new)
        shutil.copymode(root / rel, tmp)
        os.replace(tmp, destination)
        written += 1
    for dirpath, dirnames, filenames in os.walk(target):
        rel_dir = Path(dirpath).relative_to(target).as_posix()
        dirnames[:] = [d for d in dirnames if not (rel_dir == "." and BUILD_DIR_RE.match(d))]
        for name in filenames:
            rel = name if rel_dir == "." else f"{rel_dir}/{name}"
            if rel not in wanted:
                os.remove(Path(dirpath, name))
    return written


# --------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------

def stage_ranges(stages: Iterable[int]) -> str:
    """"01-02, 05": the stages, consecutive ones as a range."""
    out: List[str] = []
    run: List[int] = []
    for s in sorted(set(stages)) + [None]:
        if run and (s is None or s != run[-1] + 1):
            out.append(stage_label(run[0]) if len(run) == 1 else f"{stage_label(run[0])}-{stage_label(run[-1])}")
            run = []
        if s is not None:
            run.append(s)
    return ", ".join(out)


def describe(plan: KitPlan) -> str:
    def stages_of(regions: List[Region]) -> str:
        stages = sorted({r.stage for r in regions})
        word = "stage" if len(stages) == 1 else "stages"
        return f"{word} " + (", ".join(stage_label(s) for s in stages) or "none")
    return (f"{len(plan.files)} files; stripped {len(plan.stripped)} regions of {stages_of(plan.stripped)}; "
            f"solved {len(plan.solved)} regions of {stages_of(plan.solved)}; "
            f"left out {len(plan.left_out)} instructor-only files")


def given_away(plan: KitPlan) -> str:
    """Which answers the kit hands out: the regions it leaves solved."""
    if not plan.solved:
        return "the kit gives away no answer: every stage's regions are stripped"
    stages = sorted({r.stage for r in plan.solved})
    word = "stage" if len(stages) == 1 else "stages"
    first_stripped = min((r.stage for r in plan.stripped), default=None)
    why = (f"a kit from stage {stage_label(first_stripped)} hands out the earlier stages solved"
           if first_stripped is not None else "it strips nothing")
    regions = f"{len(plan.solved)} region" + ("" if len(plan.solved) == 1 else "s")
    return f"the kit gives away the answers of {word} {stage_ranges(stages)} ({regions}): {why}"


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        description="Write a student kit of rt: the exercise regions of the chosen stages are "
                    "replaced by bodies that throw rt::exercise_not_done.")
    parser.add_argument("target", nargs="?", help="the folder to write (new, or empty, or --force)")
    choice = parser.add_mutually_exclusive_group()
    choice.add_argument("--from-stage", type=int, metavar="N",
                        help="strip stages N and later; earlier stages are handed out solved")
    # refused with a pointer to --from-stage: a kit stripping stage N alone hands out the later ones solved
    choice.add_argument("--only-stage", type=int, metavar="N", help=argparse.SUPPRESS)
    choice.add_argument("--all", action="store_true", help="strip every stage")
    choice.add_argument("--list", action="store_true", help="list the regions and stages, write nothing")
    choice.add_argument("--check", action="store_true", help="validate the markers, write nothing")
    parser.add_argument("--source", default=str(DEFAULT_SOURCE),
                        help="the reference repository (default: the one holding this script)")
    parser.add_argument("--force", action="store_true", help="replace an existing target folder")
    args = parser.parse_args(argv)
    root = Path(args.source).resolve()
    try:
        if args.list or args.check:
            regions = scan_repository(root)
            stages = known_stages(root)
            if args.list:
                for s in sorted(stages):
                    doc = stage_doc(root, s) or "(no doc page yet)"
                    mine = [r for r in regions if r.stage == s]
                    print(f"stage {stage_label(s)}: {len(mine)} regions; tests {', '.join(stages[s])}; {doc}")
                    for r in mine:
                        print(f"  {r.where()}: {r.function}: {r.title}")
            else:
                print(f"make_kit: {len(regions)} regions in stages "
                      f"{', '.join(stage_label(s) for s in sorted({r.stage for r in regions}))}: markers valid")
            return 0
        if args.only_stage is not None:
            parser.error(f"expected --from-stage {args.only_stage} (stage {args.only_stage} and every later one "
                         f"stripped), found --only-stage {args.only_stage}: a kit stripping stage "
                         f"{args.only_stage} alone would hand out the later stages solved")
        if args.target is None or not (args.all or args.from_stage is not None):
            parser.error("give a target folder and one of --from-stage N, --all")
        chosen = select_stages(known_stages(root), args.from_stage, args.all)
        plan = plan_kit(root, chosen)
        for s in plan.missing_docs:
            print(f"make_kit: warning: stage {stage_label(s)} has no docs/stages/{stage_label(s)}-*.md; "
                  f"its messages point to docs/student-guide.md", file=sys.stderr)
        write_kit(root, plan, Path(args.target), force=args.force)
        print(f"make_kit: wrote {args.target}: {describe(plan)}")
        print(f"make_kit: {given_away(plan)}")
        return 0
    except KitError as e:
        for message in e.messages:
            print(message, file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
