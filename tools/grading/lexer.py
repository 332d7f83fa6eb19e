"""A region's text read as the compiler reads it: C++'s translation phases 1 to 3.

The grader copies the student's region lines, byte for byte, into the headers the
compiler reads (splice.compose), so what decides whether a region is safe is what GCC and
Clang make of those bytes, not what an editor shows. This lexer follows their rules and
refuses every construct whose reading depends on a rule a reader can miss:

- phase 1: a control byte other than tab and newline, a byte that is not UTF-8, a
  bidirectional-text control (the text reads otherwise than it compiles), a trigraph
  (`??=` is `#` to g++ -std=c++17 and nothing to -std=gnu++17);
- phase 2: a backslash at the end of a line (a line splice), including GCC's form with
  spaces, tabs or NULs between the backslash and the newline, and `??/` there; anywhere,
  comments and literals included;
- phase 3: comments, string and character literals with every prefix, raw strings,
  pp-numbers with digit separators, digraphs (`<%` is `{`, `<::` is `<` `::`), the
  alternative tokens (`and` is `&&`); a comment, literal or raw string left open, a
  universal character name or a non-ASCII character outside literals and comments, a
  user-defined literal suffix, a `#` or `%:` anywhere (a directive, or a macro's
  operator), and brackets that do not pair inside the region.

Every refusal is a Refusal: where, what was expected, what was found and a hint, which
splice.check_body turns into one line `file:line:col: expected ..., found ...; hint`.
Lines are the student's file's (the caller says which line the text starts on), columns
count characters from 1.
"""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

IDENT_START = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_")
IDENT_CHARS = IDENT_START | frozenset("0123456789")
DIGITS = frozenset("0123456789")

# The string and character literal prefixes of C++17; an R makes the string raw.
LITERAL_PREFIXES = frozenset({"u8", "u", "U", "L"})
RAW_PREFIXES = frozenset({"R", "u8R", "uR", "UR", "LR"})

TRIGRAPHS = {"=": "#", "/": "\\", "'": "^", "(": "[", ")": "]", "!": "|", "<": "{", ">": "}", "-": "~"}
DIGRAPHS = {"<%": "{", "%>": "}", "<:": "[", ":>": "]", "%:": "#", "%:%:": "##"}
ALTERNATIVE_TOKENS = {"and": "&&", "and_eq": "&=", "bitand": "&", "bitor": "|", "compl": "~", "not": "!",
                      "not_eq": "!=", "or": "||", "or_eq": "|=", "xor": "^", "xor_eq": "^="}
# Longest first, as the compiler takes them (C++17: no <=>, which g++ -std=c++17 reads as <= >).
PUNCTUATORS = sorted(["%:%:", "...", "->*", "<<=", ">>=", "##", "%:", "<:", ":>", "<%", "%>", "::", "->", "++",
                      "--", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||", "+=", "-=", "*=", "/=", "%=", "&=",
                      "|=", "^=", ".*", "{", "}", "[", "]", "(", ")", "<", ">", ";", ":", ",", ".", "?", "+",
                      "-", "*", "/", "%", "^", "&", "|", "~", "!", "=", "#"], key=len, reverse=True)
PUNCTUATORS_BY_FIRST: Dict[str, List[str]] = {}
for _p in PUNCTUATORS:
    PUNCTUATORS_BY_FIRST.setdefault(_p[0], []).append(_p)
OPENING = {"(": ")", "[": "]", "{": "}"}
CLOSING = {v: k for k, v in OPENING.items()}

# GCC takes a backslash followed by spaces, tabs (and the NULs it drops) before a newline
# as a line splice, with only a warning.
SPLICE_RE = re.compile(r"(\\|\?\?/)[ \t\f\v\0]*(\n|$)")
# Characters that make text display in an order other than the one it is compiled in.
# A raw string's delimiter: at most 16 printable ASCII characters, none of them a space, a
# parenthesis or a backslash (nor a quote, which no compiler needs there), then '('.
RAW_DELIMITER_RE = re.compile(r"[!#-'*-\[\]-~]{0,16}\(")
BIDI_CONTROLS = frozenset("\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")

# A function body of the course is a few dozen lines; a region far longer is no exercise,
# and would only make the grader spend its time reading it.
MAX_REGION_CHARACTERS = 100_000

DIRECTIVE_HINT = ("the grader takes only the lines between your markers, so a directive there would change "
                  "code outside your function; use the header's own #include lines")


@dataclass(frozen=True)
class Refusal:
    """Why a region is refused, at a place in the student's file."""
    line: int
    column: int
    expected: str
    found: str
    hint: str

    def message(self, rel: str) -> str:
        return f"{rel}:{self.line}:{self.column}: expected {self.expected}, found {self.found}; {self.hint}"


class Refused(Exception):
    def __init__(self, refusal: Refusal):
        super().__init__(refusal.message("<region>"))
        self.refusal = refusal


@dataclass(frozen=True)
class Token:
    """One preprocessing token. `text` is its meaning (a digraph's bracket, an alternative
    token's operator), `spelling` what was written."""
    kind: str         # "name", "number", "string", "char", "punct"
    text: str
    line: int
    column: int
    spelling: str = ""


def describe_char(ch: str) -> str:
    """A character as a message names it, never the character itself when it is invisible."""
    code = ord(ch)
    if 0xDC80 <= code <= 0xDCFF:            # a byte that did not decode (errors="surrogateescape")
        return f"a byte 0x{code - 0xDC00:02X} that is not UTF-8"
    if 0xD800 <= code <= 0xDFFF:
        return f"U+{code:04X}, which is not a character"
    if code < 0x20 or code == 0x7F:
        return f"a control byte 0x{code:02X}"
    if 0x80 <= code <= 0x9F:
        return f"a control character U+{code:04X}"
    if ch in BIDI_CONTROLS:
        return f"a bidirectional-text control U+{code:04X}"
    if code > 0x7F:
        return f"U+{code:04X} '{ch}'"
    return f"'{ch}'"


class _Text:
    """The text being lexed, with line and column of any index."""

    def __init__(self, text: str, first_line: int):
        self.text = text
        self.first_line = first_line
        self.line_starts = [0] + [m.end() for m in re.finditer("\n", text)]

    def where(self, at: int) -> Tuple[int, int]:
        index = bisect.bisect_right(self.line_starts, at) - 1      # the last line start <= at
        return self.first_line + index, at - self.line_starts[index] + 1

    def refuse(self, at: int, expected: str, found: str, hint: str) -> Refused:
        line, column = self.where(at)
        return Refused(Refusal(line, column, expected, found, hint))


# --------------------------------------------------------------------------
# Phases 1 and 2: bytes, and line splices
# --------------------------------------------------------------------------

def _check_characters(src: _Text) -> None:
    """Refuses the first character that is not text as both a reader and the compiler
    take it, and the first line splice, in the order they occur."""
    text = src.text
    for m in re.finditer(r"[^\t\n\x20-\x7e\u00a0-\ud7ff\ue000-\U0010ffff]|[\u061c\u200e\u200f\u202a-\u202e"
                         r"\u2066-\u2069]|\\|\?\?/", text):
        at, ch = m.start(), m.group()
        if ch in ("\\", "??/"):
            if SPLICE_RE.match(text, at):
                spelled = "a backslash" if ch == "\\" else "??/ (a trigraph for a backslash)"
                raise src.refuse(at, "no backslash at the end of a line", spelled + " there",
                                 "it joins the next line to this one (a line splice), even with spaces after "
                                 "it, in a comment or a string too; remove it")
            continue
        raise src.refuse(at, "text of printable characters, tabs and line ends", describe_char(ch),
                         "retype the line in a plain-text editor: this character is invisible, or is read "
                         "otherwise by the compiler than it is shown")


# --------------------------------------------------------------------------
# Phase 3: preprocessing tokens
# --------------------------------------------------------------------------

def _trigraph_at(text: str, at: int) -> Optional[str]:
    if text.startswith("??", at) and at + 2 < len(text) and text[at + 2] in TRIGRAPHS:
        return text[at:at + 3]
    return None


def _refuse_trigraph(src: _Text, at: int, trigraph: str) -> Refused:
    return src.refuse(at, "no trigraph", f"{trigraph} (a trigraph for {TRIGRAPHS[trigraph[2]]})",
                      "compilers disagree on trigraphs (g++ -std=c++17 replaces them, -std=gnu++17 does not); "
                      "write the character itself, or \\? for a question mark in a string")


class _Lexer:
    def __init__(self, src: _Text):
        self.src = src
        self.text = src.text
        self.tokens: List[Token] = []

    def add(self, kind: str, text: str, start: int, end: int) -> None:
        line, column = self.src.where(start)
        self.tokens.append(Token(kind, text, line, column, self.text[start:end]))

    def run(self) -> List[Token]:
        text, n, i = self.text, len(self.text), 0
        while i < n:
            ch = text[i]
            if ch in " \t\n":
                i += 1
            elif text.startswith("//", i):
                end = text.find("\n", i)
                i = n if end < 0 else end
            elif text.startswith("/*", i):
                end = text.find("*/", i + 2)
                if end < 0:
                    raise self.src.refuse(i, "*/ closing this comment inside the region", "the end of the region",
                                          "close the comment before RT_EXERCISE_END")
                i = end + 2
            elif _trigraph_at(text, i):
                raise _refuse_trigraph(self.src, i, _trigraph_at(text, i) or "")
            elif ch in IDENT_START:
                i = self.word(i)
            elif ch in DIGITS or (ch == "." and i + 1 < n and text[i + 1] in DIGITS):
                i = self.number(i)
            elif ch in "\"'":
                i = self.quoted(i, i)
            elif ch == "\\":
                if text.startswith(("\\u", "\\U"), i):
                    raise self.src.refuse(i, "an ASCII name", f"a universal character name {text[i:i + 6]}...",
                                          "write names in ASCII letters, digits and _; other characters belong "
                                          "in comments and strings")
                raise self.src.refuse(i, "C++", "a stray backslash", "a backslash belongs in a string or a "
                                      "character literal only")
            elif ord(ch) > 0x7E:
                raise self.src.refuse(i, "an ASCII name or symbol", describe_char(ch),
                                      "write names in ASCII letters, digits and _; other characters belong in "
                                      "comments and strings")
            else:
                i = self.punctuator(i)
        return self.tokens

    def word(self, i: int) -> int:
        text, n = self.text, len(self.text)
        j = i + 1
        while j < n and text[j] in IDENT_CHARS:
            j += 1
        word = text[i:j]
        if text.startswith(("\\u", "\\U"), j):
            raise self.src.refuse(j, "an ASCII name", f"{word} followed by a universal character name "
                                  f"{text[j:j + 6]}...", "write names in ASCII letters, digits and _")
        if j < n and (text[j] == "\\" or ord(text[j]) > 0x7E or text[j] == "$"):
            raise self.src.refuse(j, "an ASCII name", f"{word} followed by {describe_char(text[j])}",
                                  "write names in ASCII letters, digits and _ (the compiler would take the "
                                  "character as part of the name)")
        if j < n and text[j] == '"' and word in RAW_PREFIXES:
            return self.raw_string(i, j)
        if j < n and text[j] in "\"'" and word in LITERAL_PREFIXES:
            return self.quoted(i, j)
        if word in ALTERNATIVE_TOKENS:
            self.add("punct", ALTERNATIVE_TOKENS[word], i, j)
        else:
            self.add("name", word, i, j)
        return j

    def number(self, i: int) -> int:
        """A pp-number: digits, letters, _, '.', a sign after e/E/p/P, and ' between digits
        or letters (a digit separator, 1'000)."""
        text, n = self.text, len(self.text)
        j = i + 1
        while j < n:
            c = text[j]
            if c in "eEpP" and j + 1 < n and text[j + 1] in "+-":
                j += 2
            elif c in IDENT_CHARS or c == ".":
                j += 1
            elif c == "'" and j + 1 < n and text[j + 1] in IDENT_CHARS:
                j += 2
            elif c == "\\" or ord(c) > 0x7E or c == "$":
                raise self.src.refuse(j, "a number", f"{text[i:j]} followed by {describe_char(c)}",
                                      "write numbers in ASCII digits and letters")
            else:
                break
        self.add("number", text[i:j], i, j)
        return j

    def quoted(self, start: int, quote_at: int) -> int:
        """A string or character literal (its prefix from `start`), closed on its line."""
        text, n = self.text, len(self.text)
        quote = text[quote_at]
        what = "string" if quote == '"' else "character literal"
        j = quote_at + 1
        while True:
            if j >= n or text[j] == "\n":
                raise self.src.refuse(start, f"the {what} closed on its line", "the end of the line",
                                      f"add the closing {quote}")
            # a trigraph is replaced before escapes are read: "??/" is "\"
            for k in (j, j + 1) if text[j] == "\\" else (j,):
                trigraph = _trigraph_at(text, k)
                if trigraph:
                    raise _refuse_trigraph(self.src, k, trigraph)
            if text[j] == "\\":
                j += 2
                continue
            if text[j] == quote:
                break
            j += 1
        end = j + 1
        self.suffix(end, what)
        self.add("string" if quote == '"' else "char", text[start:end], start, end)
        return end

    def suffix(self, at: int, what: str) -> None:
        if at < len(self.text) and self.text[at] in IDENT_START:
            m = re.compile(r"\w+", re.ASCII).match(self.text, at)
            suffix = m.group() if m else ""
            raise self.src.refuse(at, f"the end of the {what}", f"a user-defined literal suffix {suffix}",
                                  "use the literal as it is, or convert it with a function")

    def raw_string(self, start: int, quote_at: int) -> int:
        """R"delimiter( ... )delimiter": a delimiter of at most 16 characters, none of them a
        space, a parenthesis, a backslash or a control character, closed inside the region."""
        text = self.text
        m = RAW_DELIMITER_RE.match(text, quote_at + 1)
        if not m:
            raise self.src.refuse(start, "a raw string R\"delimiter(...)delimiter\" whose delimiter has at most 16 "
                                  "characters and no space, parenthesis or backslash",
                                  re.split(r"[(\n]", text[start:quote_at + 19])[0],
                                  "check the opening of the raw string")
        delimiter = m.group()[:-1]
        closing = ")" + delimiter + '"'
        close = text.find(closing, m.end())
        if close < 0:
            raise self.src.refuse(start, "the raw string closed inside the region", "the end of the region",
                                  f"close it with {closing} before RT_EXERCISE_END")
        for k in range(m.end(), close):
            trigraph = _trigraph_at(text, k)
            if trigraph:
                raise _refuse_trigraph(self.src, k, trigraph)
        end = close + len(closing)
        self.suffix(end, "raw string")
        self.add("string", text[start:end], start, end)
        return end

    def punctuator(self, i: int) -> int:
        text = self.text
        # <:: is < followed by :: unless the next character is : or > (C++11 [lex.pptoken])
        if text.startswith("<::", i) and not text.startswith(("<:::", "<::>"), i):
            self.add("punct", "<", i, i + 1)
            return i + 1
        for p in PUNCTUATORS_BY_FIRST.get(text[i], ()):
            if text.startswith(p, i):
                if p in ("#", "%:", "##", "%:%:"):
                    m = re.compile(r"[ \t]*([A-Za-z_]\w*)?").match(text, i + len(p))
                    word = m.group(1) if m and m.group(1) else ""
                    raise self.src.refuse(i, "no preprocessor directive in an exercise region",
                                          f"#{word}" if word else f"{p}", DIRECTIVE_HINT)
                self.add("punct", DIGRAPHS.get(p, p), i, i + len(p))
                return i + len(p)
        raise self.src.refuse(i, "C++", describe_char(text[i]), "this character is no part of C++ outside a "
                              "string or a comment")


def tokens(text: str, first_line: int = 1) -> List[Token]:
    """The tokens of a region's text, whose first line is `first_line` of the student's file;
    raises Refused for the first construct the grader does not take (see the module)."""
    src = _Text(text, first_line)
    if len(text) > MAX_REGION_CHARACTERS:
        raise src.refuse(0, f"a function body of at most {MAX_REGION_CHARACTERS} characters",
                         f"{len(text)} of them", "an exercise needs a few dozen lines; keep helpers small")
    _check_characters(src)
    return _Lexer(src).run()


def header_tokens(text: str) -> List[Token]:
    """The tokens of a header of the reference, outside its preprocessor directives: its
    line splices joined and its directive lines left out (names.py reads the names the
    reference uses). Positions are approximate; the reference is trusted."""
    text = re.sub(r"\\[ \t]*\n", "", text.replace("\r\n", "\n"))
    kept = ["" if line.lstrip().startswith("#") else line for line in text.split("\n")]
    return _Lexer(_Text("\n".join(kept), 1)).run()


# --------------------------------------------------------------------------
# Brackets
# --------------------------------------------------------------------------

def match_brackets(toks: List[Token]) -> Dict[int, int]:
    """Each bracket's partner (both ways), by token index; raises Refused for a closing
    bracket with no partner (it would close the function), a pair that does not match,
    and a bracket left open at the end of the region."""
    stack: List[int] = []
    partner: Dict[int, int] = {}
    for k, t in enumerate(toks):
        if t.kind != "punct":
            continue
        if t.text in OPENING:
            stack.append(k)
        elif t.text in CLOSING:
            if not stack:
                raise Refused(Refusal(t.line, t.column, "code that stays inside the function body",
                                      f"an unmatched '{t.spelling}'",
                                      "the region is the function's whole body: keep its braces balanced"))
            at = stack.pop()
            opening = toks[at]
            if opening.text != CLOSING[t.text]:
                raise Refused(Refusal(t.line, t.column, f"a bracket closing the '{opening.spelling}' of line "
                                      f"{opening.line}", f"'{t.spelling}'", "check the brackets"))
            partner[k], partner[at] = at, k
    if stack:
        opening = toks[stack[-1]]
        closing = OPENING[opening.text]
        raise Refused(Refusal(opening.line, opening.column, f"'{closing}' for this '{opening.spelling}' before "
                              f"RT_EXERCISE_END", "the end of the region",
                              "the region is the function's whole body: keep its brackets balanced"))
    return partner
