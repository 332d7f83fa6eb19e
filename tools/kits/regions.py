"""kits.regions - the exercise regions of a C++ file: the markers

    // RT_EXERCISE_BEGIN(stageNN: short title)
    ...
    // RT_EXERCISE_END

found and checked, and the signature of the function around each (its name,
its parameters, for the stub's (void) lines), by a scanner of C++ that knows
comments, strings, templates and braces. Every problem is one line
"file:line:col: expected X, found Y; hint", collected in a KitError.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Set, Tuple

BEGIN_RE = re.compile(r"^RT_EXERCISE_BEGIN\((?P<inside>.*)\)$")
BEGIN_INSIDE_RE = re.compile(r"^stage(?P<stage>[0-9]{2}):\s*(?P<title>\S.*?)\s*"
                             r"(?:;\s*repeats\s+(?P<repeats>stage[0-9]{2}(?:\s*,\s*stage[0-9]{2})*)\s*)?$")
END_RE = re.compile(r"^RT_EXERCISE_END$")
HINT_RE = re.compile(r"^hint\b", re.IGNORECASE)


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
