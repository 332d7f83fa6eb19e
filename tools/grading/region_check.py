"""The allow-list applied to a region's tokens (lexer.py makes them, names.py holds the lists).

Every name a region writes must be one the lists allow where it stands:
- after `.` or `->`, a member of rt's types, GLM's vectors, the vetted containers, or of a
  type the region declares;
- after `std::`, `glm::`, `rt::`, `detail::` or one of rt's scopes (`projection::`), a name
  of that list; `::name` only for ::std, ::glm and ::rt; after `>::`, a nested name;
- unqualified, a name of rt's API, a parameter, a type of rt's, a vetted standard or GLM
  name, or a name the region declared and whose scope has not ended.

A region's own declarations: a name is declared where it follows a type (a keyword, one of
rt's, GLM's or the vetted standard types, a closing `>` of such a template's arguments,
`decltype(...)` or `auto`, then `*`, `&`, `const`), followed by `=`, `;`, `,`, `{`, `(`, `)`,
`[` or `:`; in the later declarators of a declaration that started a statement (outside a
`?:` and template arguments); in a structured binding `auto [a, b]`; in a lambda's
init-capture `[x = ...]`; and after `struct`, `enum` or `using name =`. Its scope ends where
C++'s does (the block, the lambda, the statement of a for or if), so that a name declared and
gone out of scope is checked again: `{ int fopen = 0; } fopen(...)` is refused. A type only
counts as one while no local or parameter of the same name hides it, so `ok && system, ...`
cannot pass for a declaration. A declaration whose parentheses hold a type (`int
system(const char*);`) redeclares the library's function and is refused outside a local class.

Beyond names: attributes other than the standard ones, casts to pointers or references and
from what is visibly a pointer (`&x`, a string, nullptr, a local declared with `*` or `[]`,
`.data()`), reinterpret_cast and const_cast, `using` of anything but rt and GLM, and the
keywords of names.REFUSED_KEYWORDS.

Known gaps, which the judge's sandbox covers: a pointer held in a variable the region did not
visibly make a pointer (an array parameter, `auto p = v.begin()` on a std::array) can be cast
to an integer; the type of an expression is not known, so a cast from a pointer is seen only
where the operand shows it; and C++ is not memory-safe, so an index past an array's end or
pointer arithmetic reaches any memory without naming anything. The rule errs towards
refusing: a name used before its declaration in a local class is refused, as is a lambda
whose body the scanner cannot find.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, FrozenSet, List, Optional, Set, Tuple

from . import names
from .lexer import Refusal, Refused, Token

DECLARATOR_FOLLOW = frozenset({"=", ";", ",", "{", "(", ")", "[", ":"})
PTR_OPS = frozenset({"*", "&", "&&"})
CONTROL = frozenset({"for", "while", "switch", "if", "catch"})
# A '(' after one of these is no cast: an operand, a condition or a type.
NOT_A_CAST_AFTER = frozenset({"sizeof", "alignof", "decltype", "typeid", "noexcept", "alignas", "operator",
                              "for", "while", "switch", "if", "catch", "static_assert"})
STD_HEADERS = ("<cmath>, <algorithm>, <numeric>, <limits>, <array>, <vector>, <utility>, <optional>, <string> "
               "or <cstdint>")
GROUP_HINTS = {
    "process": "the tests call only the function itself: it returns its answer and may not end, start or "
               "signal a process",
    "io": "the tests call only the function itself: return the result; do not print it or read or write files",
    "environment": "an exercise computes from its arguments only, not from the environment, the clock or the "
                   "machine",
}


@dataclass
class _Declaration:
    name: str
    kind: str          # "value", "pointer" (a value that is a pointer or an array) or "type"
    start: int
    end: int


@dataclass
class _Statement:
    """A declaration statement in progress: its later declarators follow top-level commas."""
    depth: int
    start: int
    ternary: int = 0
    scope_end: Optional[int] = None      # set when the statement is an if's, a loop's or an else's


@dataclass
class _Walk:
    toks: List[Token]
    partner: Dict[int, int]
    ppm: bool = False
    shadowing: FrozenSet[str] = frozenset()        # the enclosing functions' parameters
    # by name, each a stack whose entries out of scope are dropped as the walk passes them
    declarations: Dict[str, List[_Declaration]] = field(default_factory=dict)
    declared_names: Set[str] = field(default_factory=set)   # every name the region declares
    declared_types: Set[str] = field(default_factory=set)   # every type it declares
    declared_at: Set[int] = field(default_factory=set)      # name tokens already taken as declarators
    stack: List[int] = field(default_factory=list)          # open brackets
    statements: List[_Statement] = field(default_factory=list)
    angle_opener: Dict[int, int] = field(default_factory=dict)   # '>' closing a type template's -> its '<'
    angle_ends: Set[int] = field(default_factory=set)
    open_angles: List[Tuple[int, int]] = field(default_factory=list)   # ('<', '>') of those still open
    decltype_ends: Set[int] = field(default_factory=set)
    lambda_bodies: Dict[int, int] = field(default_factory=dict)   # '(' of a lambda's parameters -> its '}'
    class_bodies: Set[int] = field(default_factory=set)     # '{' of a local struct or class
    skip_to: int = -1                                       # tokens before it are checked already

    # ------------------------------------------------------------------
    def refuse(self, k: int, expected: str, found: str, hint: str) -> Refused:
        t = self.toks[min(k, len(self.toks) - 1)]
        return Refused(Refusal(t.line, t.column, expected, found, hint))

    def text(self, k: int) -> str:
        return self.toks[k].text if 0 <= k < len(self.toks) else ""

    def is_name(self, k: int) -> bool:
        return 0 <= k < len(self.toks) and self.toks[k].kind == "name"

    def run(self) -> None:
        k = 0
        while k < len(self.toks):
            t = self.toks[k]
            if k < self.skip_to:
                pass
            elif t.kind == "punct":
                self.punct(k)
            elif t.kind == "name":
                self.name(k)
            self.brackets(k)
            k += 1

    # ------------------------------------------------------------------
    # Scopes
    # ------------------------------------------------------------------
    def in_scope(self, name: str, k: int) -> List[_Declaration]:
        stack = self.declarations.get(name)
        if not stack:
            return []
        while stack and stack[-1].end < k:      # scopes nest: the last one ends first
            stack.pop()
        return [d for d in stack if d.start <= k <= d.end]

    def declare(self, k: int, kind: str, end: Optional[int] = None) -> None:
        """The name at token `k` declared, its scope from `k` to where C++ ends it (`end`
        when the caller knows it better than the brackets do)."""
        self.remember(_Declaration(self.text(k), kind, k, self.scope_end(self.stack) if end is None else end))

    def remember(self, d: _Declaration) -> None:
        stack = self.declarations.setdefault(d.name, [])
        while stack and stack[-1].end < d.start:
            stack.pop()
        stack.append(d)
        self.declared_names.add(d.name)
        if d.kind == "type":
            self.declared_types.add(d.name)
        self.declared_at.add(d.start)

    def substatement_end(self, start: int) -> Optional[int]:
        """When the declaration starting at `start` is the whole body of an if, else, loop or
        do without braces, the end of that body: its scope ends there (`if (c) int fopen = 0;
        fopen(...)` calls the library's fopen)."""
        before = start - 1
        if self.text(before) in ("else", "do"):
            return self.statement_end(start)
        if self.text(before) == ")":
            keyword = self.partner[before] - 1
            if self.text(keyword) == "constexpr":
                keyword -= 1
            if self.text(keyword) in CONTROL:
                return self.statement_end(start)
        return None

    def scope_end(self, stack: List[int]) -> int:
        if not stack:
            return len(self.toks)
        opener = stack[-1]
        if self.text(opener) == "(":
            if opener in self.lambda_bodies:
                return self.lambda_bodies[opener]
            before = opener - 1
            if self.text(before) == "constexpr":
                before -= 1
            if self.text(before) in CONTROL:            # the whole statement, an if's else too
                return self.statement_end(before)
        return self.partner[opener]

    def statement_end(self, j: int) -> int:
        """The last token of the statement starting at `j`."""
        n = len(self.toks)
        if j >= n:
            return n
        word = self.text(j)
        if word == "{":
            return self.partner[j]
        if word in ("for", "while", "switch", "catch") and self.text(j + 1) == "(":
            return self.statement_end(self.partner[j + 1] + 1)
        if word == "if":
            k = j + 1 + (self.text(j + 1) == "constexpr")
            if self.text(k) != "(":
                return n
            end = self.statement_end(self.partner[k] + 1)
            if self.text(end + 1) == "else":
                return self.statement_end(end + 2)
            return end
        if word == "do":
            end = self.statement_end(j + 1)
            return self.statement_end(end + 1)          # while (...);
        if word == "try":
            end = self.statement_end(j + 1)
            while self.text(end + 1) == "catch":
                end = self.statement_end(end + 1)
            return end
        k = j
        while k < n and self.text(k) != ";":
            if self.text(k) in ("(", "[", "{"):
                k = self.partner[k]
            elif self.text(k) in (")", "]", "}"):
                return k - 1
            k += 1
        return min(k, n)

    # ------------------------------------------------------------------
    # Types
    # ------------------------------------------------------------------
    def qualifier(self, k: int) -> Optional[str]:
        """The qualifier of the name at `k`: "std" for std::x, "" for ::x, None when unqualified."""
        if self.text(k - 1) != "::":
            return None
        return self.text(k - 2) if self.is_name(k - 2) else ""

    def hidden(self, name: str, k: int) -> bool:
        """Whether a parameter or a value the region declared hides the type `name` at `k`."""
        return name in self.shadowing or any(d.kind != "type" for d in self.in_scope(name, k))

    def names_a_type(self, k: int) -> bool:
        """Whether the name at `k` is surely a type there."""
        if not self.is_name(k):
            return False
        word = self.text(k)
        if word in names.TYPE_KEYWORDS:
            return True
        q = self.qualifier(k)
        if q is None:
            if any(d.kind == "type" for d in self.in_scope(word, k)) and not self.hidden(word, k):
                return True
            return word in names.type_names("") and not self.hidden(word, k)
        return word in names.type_names(q)

    def names_a_type_template(self, k: int) -> bool:
        word, q = self.text(k), self.qualifier(k)
        if q is None:
            return word in names.type_templates("") and not self.hidden(word, k)
        return word in names.type_templates(q)

    def type_ends_at(self, k: int) -> bool:
        return self.names_a_type(k) or k in self.angle_ends or k in self.decltype_ends

    def angle_end(self, lt: int) -> Optional[int]:
        """The '>' closing the template arguments opened at `lt` ('>>' closes two)."""
        depth, k = 0, lt
        while k < len(self.toks):
            word = self.text(k)
            if word in ("(", "[", "{") and k != lt:
                k = self.partner[k]
            elif word in (";", "{", "}", ")", "]"):
                return None
            elif word == "<":
                depth += 1
            elif word in (">", ">>"):
                depth -= 1 if word == ">" else 2
                if depth <= 0:
                    return k
            k += 1
        return None

    def type_start(self, k: int) -> int:
        """The first token of the declaration's specifiers whose type ends at `k`."""
        j = k + 1           # each step looks at the token before j
        while j > 0:
            word = self.text(j - 1)
            if j - 1 in self.angle_ends:
                j = self.angle_opener[j - 1]
            elif j - 1 in self.decltype_ends:
                j = self.partner[j - 1] - 1
            elif word == "::" or word in names.CV or word in ("constexpr", "typename", "inline") \
                    or (self.is_name(j - 1) and word not in names.KEYWORDS) or word in names.TYPE_KEYWORDS:
                j -= 1
            else:
                break
        return j

    def starts_statement(self, j: int) -> bool:
        before = self.text(j - 1) if j > 0 else ";"
        if before in (";", "{", "}", ")", ":", "else", "do"):
            return True
        return before == "(" and self.text(j - 2) in CONTROL

    # ------------------------------------------------------------------
    # Punctuation
    # ------------------------------------------------------------------
    def brackets(self, k: int) -> None:
        word = self.text(k)
        if self.toks[k].kind != "punct":
            return
        if word in ("(", "[", "{"):
            self.stack.append(k)
        elif word in (")", "]", "}"):
            self.stack.pop()
            while self.statements and self.statements[-1].depth > len(self.stack):
                self.statements.pop()
        while self.open_angles and self.open_angles[-1][1] == k:     # '>>' may close two
            self.open_angles.pop()
        if word == ";":
            while self.statements and self.statements[-1].depth >= len(self.stack):
                self.statements.pop()

    def punct(self, k: int) -> None:
        word = self.text(k)
        if word == "[" and self.text(k + 1) == "[":
            self.attribute(k)
        elif word == "[":
            self.square(k)
        elif word == "(":
            self.c_cast(k)
        elif word == ",":
            self.next_declarator(k)
        elif word in ("?", ":") and self.statements and self.statements[-1].depth == len(self.stack):
            st = self.statements[-1]
            st.ternary = st.ternary + 1 if word == "?" else max(0, st.ternary - 1)

    def attribute(self, k: int) -> None:
        """[[...]]: only the standard attributes, unscoped, with at most a string argument."""
        inner = k + 1
        close = self.partner[inner]
        if self.partner[k] != close + 1:
            raise self.refuse(k, "an attribute [[...]]", "'[[' that does not close with ']]'",
                              "two [ in a row start an attribute in C++")
        j = inner + 1
        if self.text(j) == "using":
            raise self.refuse(j, "a standard attribute ([[maybe_unused]] and the like)", "[[using",
                              "write the function in C++ only: attributes of a vendor's namespace can place "
                              "code where it runs before the tests")
        while j < close:
            if not self.is_name(j):
                raise self.refuse(j, "a standard attribute", f"'{self.toks[j].spelling}' in [[...]]",
                                  "write [[maybe_unused]], [[fallthrough]], [[nodiscard]] and the like")
            if self.text(j + 1) == "::":
                raise self.refuse(k, "no attribute with a vendor's prefix in an exercise region",
                                  f"[[{self.text(j)}::{self.text(j + 2)}",
                                  "write the function in C++ only; [[maybe_unused]] and the like are fine")
            if self.text(j) not in names.STANDARD_ATTRIBUTES:
                raise self.refuse(j, "a standard attribute", f"[[{self.text(j)}]]",
                                  "write [[maybe_unused]], [[fallthrough]], [[nodiscard]] and the like")
            j += 1
            if self.text(j) == "(":
                end = self.partner[j]
                if not (end == j + 2 and self.toks[j + 1].kind == "string"):
                    raise self.refuse(j, "a string as the attribute's argument", "another argument",
                                      "give [[deprecated]] or [[nodiscard]] a string, or no argument")
                j = end + 1
            if self.text(j) == "...":
                j += 1
            if self.text(j) == ",":
                j += 1
            elif j != close:
                raise self.refuse(j, "',' or ']]' in the attribute", f"'{self.toks[j].spelling}'",
                                  "write [[maybe_unused]] and the like")
        self.skip_to = close + 2

    def square(self, k: int) -> None:
        """A '[' that opens a lambda's captures or a structured binding (not a subscript)."""
        prev = self.toks[k - 1] if k else None
        if prev is not None and (prev.kind in ("string", "char", "number") or prev.text in (")", "]", "}")
                                 or (prev.kind == "name" and (prev.text not in names.KEYWORDS
                                                              or prev.text in ("this", "operator")))
                                 or k - 1 in self.angle_ends):
            return
        close = self.partner[k]
        if prev is not None and (prev.text == "auto" or (prev.text in ("&", "&&") and self.text(k - 2) == "auto")):
            end = self.substatement_end(self.type_start(k - 1 if prev.text == "auto" else k - 2))
            for j in range(k + 1, close):                     # auto [a, b]: each name is declared
                if self.is_name(j):
                    self.declare(j, "value", end)
                elif self.text(j) != ",":
                    raise self.refuse(j, "names in the structured binding", f"'{self.toks[j].spelling}'",
                                      "write auto [a, b] = ...")
            self.skip_to = close
            return
        body = self.lambda_body(close)
        if body is None:
            return
        j = k + 1
        while j < close:                                      # init-captures: [x = e], [&x = e]
            start = j + 1 if self.text(j) == "&" else j
            if self.is_name(start) and self.text(start + 1) in ("=", "{", "(") and self.text(start) != "this":
                self.remember(_Declaration(self.text(start), "value", start, body))
            while j < close and self.text(j) != ",":
                j = self.partner[j] + 1 if self.text(j) in ("(", "[", "{") else j + 1
            j += 1

    def lambda_body(self, close: int) -> Optional[int]:
        """The '}' of the lambda whose captures end at `close`; its parameters' '(' is noted."""
        j = close + 1
        if self.text(j) == "(":
            params = j
            j = self.partner[j] + 1
        else:
            params = None
        while j < len(self.toks) and self.text(j) != "{":
            if self.text(j) in (";", ")", "]", "}"):
                return None
            j = self.partner[j] + 1 if self.text(j) in ("(", "[") else j + 1
        if j >= len(self.toks):
            return None
        body = self.partner[j]
        if params is not None:
            self.lambda_bodies[params] = body
        return body

    def next_declarator(self, k: int) -> None:
        """A ',' of a declaration statement: the name after it (past * and &) is declared."""
        if not self.statements:
            return
        st = self.statements[-1]
        if st.depth != len(self.stack) or st.ternary or any(lt > st.start for lt, _ in self.open_angles):
            return
        j = k + 1
        pointer = False
        while self.text(j) in PTR_OPS or self.text(j) in names.CV:
            pointer = pointer or self.text(j) == "*"
            j += 1
        if self.is_name(j) and self.text(j) not in names.KEYWORDS and self.qualifier(j) is None \
                and self.text(j + 1) in DECLARATOR_FOLLOW - {":", ")"}:
            self.check_not_a_function(j)
            self.declare(j, "pointer" if pointer or self.text(j + 1) == "[" else "value", st.scope_end)

    # ------------------------------------------------------------------
    # Casts
    # ------------------------------------------------------------------
    def c_cast(self, k: int) -> None:
        """(type)operand: no pointer or reference type, no operand that is visibly a pointer."""
        prev = self.toks[k - 1] if k else None
        if prev is not None and (prev.text in (")", "]", ">", ">>") or prev.text in NOT_A_CAST_AFTER
                                 or (prev.kind == "name" and prev.text not in ("return", "throw", "case", "else",
                                                                                "do", "new", "delete"))):
            return
        close = self.partner[k]
        if not self.type_id(k + 1, close):
            return
        spelled = " ".join(self.text(j) for j in range(k + 1, close))
        if any(self.text(j) in PTR_OPS for j in range(k + 1, close)):
            raise self.refuse(k, "a cast to a number or a value type", f"a cast to ({spelled})",
                              "a cast to a pointer or a reference can make one to any address; an exercise "
                              "needs none")
        if any(self.text(j) in names.ARITHMETIC_TYPES for j in range(k + 1, close)) \
                and self.pointer_operand(close + 1):
            raise self.refuse(k, "a cast of a number or a value", f"({spelled}) of a pointer",
                              "a pointer's address is no value an exercise computes with")

    def type_id(self, start: int, end: int) -> bool:
        """Whether tokens start..end-1 are a type alone: specifiers, a type, then * and &."""
        j, saw_type = start, False
        while j < end:
            word = self.text(j)
            if word in names.CV or word in ("typename", "struct", "class", "enum"):
                j += 1
            elif word == "::" or (self.is_name(j) and self.text(j + 1) == "::"):
                j += 1
            elif self.names_a_type(j):
                saw_type = True
                j += 1
                if self.text(j) == "<" and self.names_a_type_template(j - 1):
                    close = self.angle_end(j)
                    if close is None or close >= end:
                        return False
                    j = close + 1
            elif word in PTR_OPS and saw_type:
                j += 1
            else:
                return False
        return saw_type

    def pointer_operand(self, j: int) -> bool:
        """Whether the operand starting at `j` is visibly a pointer."""
        t = self.toks[j] if j < len(self.toks) else None
        if t is None:
            return False
        if t.text in ("&", "&&") and t.kind == "punct":
            return True
        if t.kind == "string" or t.text in ("nullptr", "this"):
            return True
        if t.text == "+" and self.text(j + 1) == "[":
            return True                                   # +[]{...}: a lambda made a function pointer
        if t.text == "(":
            return self.pointer_operand(j + 1)
        if t.kind != "name":
            return False
        if any(d.kind == "pointer" for d in self.in_scope(t.text, j)) and self.text(j + 1) not in ("[", "(", ".",
                                                                                                   "->"):
            return True
        last, k = "", j + 1                               # x.y(...).data(): a pointer to the elements
        while k < len(self.toks):
            if self.text(k) in (".", "->") and self.is_name(k + 1):
                last, k = self.text(k + 1), k + 2
            elif self.text(k) in ("(", "["):
                k = self.partner[k] + 1
            else:
                break
        return last in ("data", "c_str") and self.text(k - 1) == ")"

    def named_cast(self, k: int) -> None:
        word = self.text(k)
        if self.text(k + 1) != "<":
            raise self.refuse(k, f"{word}<type>(...)", word, "write the type to convert to in < >")
        close = self.angle_end(k + 1)
        if close is None:
            raise self.refuse(k, f"{word}<type>(...)", word, "close the type with >")
        target = [self.text(j) for j in range(k + 2, close)]
        spelled = f"{word}<{' '.join(target)}>"
        if word == "reinterpret_cast":
            if self.ppm and target in (["const", "char", "*"], ["char", "const", "*"]):
                return
            raise self.refuse(k, "no reinterpret_cast in an exercise region" if not self.ppm
                              else "reinterpret_cast<const char*> only", spelled,
                              "it reads one type's bytes as another's; only the PPM writer needs one, "
                              "reinterpret_cast<const char*>(bytes.data()) for std::ostream::write")
        if any(w in PTR_OPS or w == "decltype" or w in names.rt_names().pointer_aliases for w in target):
            raise self.refuse(k, "a cast to a number or a value type", spelled,
                              "a cast to a pointer or a reference can make one to any address; an exercise "
                              "needs none")
        if any(w in names.ARITHMETIC_TYPES for w in target) and self.text(close + 1) == "(" \
                and self.pointer_operand(close + 2):
            raise self.refuse(k, "a cast of a number or a value", f"{spelled} of a pointer",
                              "a pointer's address is no value an exercise computes with")

    # ------------------------------------------------------------------
    # Names
    # ------------------------------------------------------------------
    def name(self, k: int) -> None:
        word = self.text(k)
        if word in names.KEYWORDS:
            self.keyword(k)
            return
        self.reserved(k)
        if word in names.TEST_FRAMEWORK or word.startswith("DOCTEST_"):
            raise self.refuse(k, "no use of the test framework in an exercise region", word,
                              "the library's code does not call doctest")
        if self.text(k + 1) == "<" and self.names_a_type_template(k):
            close = self.angle_end(k + 1)
            if close is not None:
                self.angle_opener.setdefault(close, k + 1)     # the outer one, when '>>' closes two
                self.angle_ends.add(close)
                self.open_angles.append((k + 1, close))
        prev = self.text(k - 1) if k else ""
        if prev in (".", "->"):
            self.member(k)
        elif prev == "::":
            self.qualified(k)
        elif k in self.declared_at:
            pass
        elif not self.declarator(k):
            self.unqualified(k)
        if word in names.ARITHMETIC_TYPES and self.names_a_type(k) and self.text(k + 1) == "(" \
                and self.pointer_operand(k + 2):
            raise self.refuse(k, "a conversion of a number or a value", f"{word}(...) of a pointer",
                              "a pointer's address is no value an exercise computes with")

    def reserved(self, k: int) -> None:
        word = self.text(k)
        if word in names.DENIED:
            return                  # _Exit and the like: refused with what they do, where they stand
        if word in names.RESERVED_MEANING:
            what = names.RESERVED_MEANING[word]
            raise self.refuse(k, f"no {what} in an exercise region", word, "write the function in C++ only")
        if word.startswith("__") or "__" in word or (word.startswith("_") and word[1:2].isupper()):
            raise self.refuse(k, "a name that is not reserved to the compiler", word,
                              "names with two underscores, or an underscore and a capital, are the compiler's "
                              "and its library's; choose another")

    def declarator(self, k: int) -> bool:
        """Declares the name at `k` when it stands where a declaration names what it declares."""
        if self.text(k + 1) not in DECLARATOR_FOLLOW:
            return False
        j, pointer = k - 1, False
        while j >= 0 and (self.text(j) in PTR_OPS or self.text(j) in names.CV):
            pointer = pointer or self.text(j) == "*"
            j -= 1
        if j < 0 or not self.type_ends_at(j):
            return False
        self.check_not_a_function(k)
        array = self.text(k + 1) == "["
        auto_pointer = self.text(j) == "auto" and self.text(k + 1) == "=" and self.pointer_operand(k + 2)
        start = self.type_start(j)
        end = self.substatement_end(start)
        self.declare(k, "pointer" if pointer or array or auto_pointer else "value", end)
        if self.starts_statement(start):
            self.statements.append(_Statement(len(self.stack), start, scope_end=end))
        return True

    def check_not_a_function(self, k: int) -> None:
        """T name(type ...); at block scope declares the library's function `name` again."""
        if self.text(k + 1) != "(" or (self.stack and self.stack[-1] in self.class_bodies):
            return
        j = k + 2
        first = self.text(j)
        while self.text(j) in names.CV or self.text(j) == "::" or (self.is_name(j) and self.text(j + 1) == "::"):
            j += 1
        typed = first == ")" or first in names.CV or self.names_a_type(j)
        after = self.text(j + 1)
        if first == ")" or (typed and after not in ("(", "{", ".", "->")):
            raise self.refuse(k, "a variable", f"a declaration of a function {self.text(k)}(...)",
                              "a block-scope function declaration names a function outside the region; to "
                              "make a value write T x{...} or T x = T(...)")

    def unqualified(self, k: int) -> None:
        word = self.text(k)
        if self.in_scope(word, k) or word in names.CONTEXTUAL:
            return
        if word in names.unqualified(self.ppm) and (word not in names.DENIED):
            return
        group = names.denied_group(word)
        hint = GROUP_HINTS.get(group) or (
            f"declare it in the region before using it; rt's names are in tests/public_names.txt, and the "
            f"standard library's the region may use are from {STD_HEADERS}")
        raise self.refuse(k, "a name declared before this point, or one of rt's API, GLM or the vetted standard "
                             "library", word, hint)

    def qualified(self, k: int) -> None:
        word, q = self.text(k), self.qualifier(k)
        prev2 = self.text(k - 2) if k >= 2 else ""
        if q == "":
            if k - 2 in self.angle_ends or prev2 == ")":      # T<...>::x, decltype(...)::x
                if word in names.STD_MEMBERS or word in names.members(self.ppm):
                    return
                raise self.refuse(k, "a member or nested name", f"::{word}", "use the type's own members")
            if word in ("std", "glm", "rt"):
                return
            raise self.refuse(k - 1, "::std, ::glm or ::rt after a leading ::", f"::{word}",
                              GROUP_HINTS.get(names.denied_group(word),
                                              "a leading :: names the global namespace; use rt's API"))
        assert q is not None
        if q in self.declared_types and word in self.declared_names:
            return                                         # my_enum::value, of a type of the region
        if word in names.after_qualifier(q, self.ppm):
            return
        if q == "std":
            raise self.refuse(k - 2, f"a name from {STD_HEADERS}", f"std::{word}",
                              GROUP_HINTS.get(names.denied_group(word),
                                              "the region may use the standard library's math, algorithms, "
                                              "containers and limits only"))
        if q == "glm":
            raise self.refuse(k - 2, "a function or type of GLM's vector algebra", f"glm::{word}",
                              "use glm's public functions (dot, cross, normalize, length ...), not glm::detail")
        if q == "rt":
            raise self.refuse(k - 2, "a name of rt's API (tests/public_names.txt) that does no I/O",
                              f"rt::{word}", GROUP_HINTS["io"] if word in names.RT_REFUSED else
                              "rt::detail is not API; use the names in tests/public_names.txt")
        if q == "detail":
            raise self.refuse(k - 2, "a name of rt's API", f"detail::{word}",
                              "rt::detail is not API; use the names in tests/public_names.txt")
        raise self.refuse(k - 2, f"a name rt declares in {q}", f"{q}::{word}",
                          "write the enumerators and members as rt's headers name them")

    def member(self, k: int) -> None:
        word = self.text(k)
        if word in names.members(self.ppm) or word in self.declared_names or word in names.CONTEXTUAL:
            return
        if word in names.PPM_MEMBERS or word in names.DENIED_MEMBERS:
            hint = "only the PPM writer writes to a stream, with << and write" if word in names.PPM_MEMBERS \
                else GROUP_HINTS["io"]
        else:
            hint = "use the members that rt's headers, GLM and the vetted containers declare"
        raise self.refuse(k, "a member of rt's types, GLM's vectors or the standard containers",
                          f".{word}", hint)

    # ------------------------------------------------------------------
    # Keywords
    # ------------------------------------------------------------------
    def keyword(self, k: int) -> None:
        word = self.text(k)
        if word in names.REFUSED_KEYWORDS:
            expected, hint = names.REFUSED_KEYWORDS[word]
            raise self.refuse(k, expected, word, hint)
        if word in ("reinterpret_cast", "static_cast", "dynamic_cast"):
            self.named_cast(k)
        elif word == "decltype" and self.text(k + 1) == "(":
            close = self.partner[k + 1]
            self.decltype_ends.add(close)
            if self.text(close + 1) == "(":
                raise self.refuse(k, "a conversion to a named type", "decltype(...)(...)",
                                  "write static_cast<type>(...)")
        elif word in ("struct", "class", "enum"):
            self.local_type(k)
        elif word == "using":
            self.using(k)
        elif word == "auto" and self.text(k + 1) == "(":
            raise self.refuse(k, "auto followed by a name", "auto(", "write auto name = ...")

    def local_type(self, k: int) -> None:
        """struct X { ... }, enum [class] X [: T] { ... }: a type the region defines."""
        j = k + 1
        if self.text(k) == "enum" and self.text(j) in ("class", "struct"):
            j += 1
        named = self.is_name(j) and self.text(j) not in names.KEYWORDS
        brace = j + 1 if named else j
        while brace < len(self.toks) and self.text(brace) not in ("{", ";", "(", ")", "="):
            brace += 1
        if self.text(brace) != "{" or (named and self.text(j + 1) not in ("{", ":", "final")):
            spelled = f"{self.text(k)} {self.text(j)}"
            raise self.refuse(k, f"a {self.text(k)} defined here ({self.text(k)} name {{ ... }})", spelled,
                              "name a type of your own only where you define it; an elaborated "
                              f"{self.text(k)} name refers to one outside the region")
        if named:
            self.declare(j, "type")
        if self.text(k) == "enum":
            body_end = self.partner[brace]
            m = brace + 1
            while m < body_end:                      # its enumerators, in the scope around it
                if self.is_name(m) and self.text(m - 1) in ("{", ","):
                    self.declare(m, "value")
                m = self.partner[m] + 1 if self.text(m) in ("(", "[", "{") else m + 1
        else:
            self.class_bodies.add(brace)

    def using(self, k: int) -> None:
        j = k + 1
        if self.text(j) == "namespace":
            m = j + 1 + (self.text(j + 1) == "::")
            if self.text(m) in ("rt", "glm") and self.text(m + 1) == ";":
                self.skip_to = m + 1
                return
            raise self.refuse(k, "using namespace rt or glm only", f"using namespace {self.text(m)}",
                              "qualify the standard library's names with std:: instead")
        if self.is_name(j) and self.text(j + 1) == "=":
            end = j + 2
            while end < len(self.toks) and self.text(end) != ";":
                word = self.text(end)
                if word in PTR_OPS or word == "decltype" or (word == "(" and self.text(end + 1) == "*"):
                    raise self.refuse(end, "an alias of a value type", f"'{self.toks[end].spelling}' in the alias",
                                      "an alias of a pointer or a reference type would make a cast to one")
                end = self.partner[end] if word in ("(", "[", "{") else end
                end += 1
            self.declare(j, "type")
            return
        m = j + (self.text(j) == "::")
        if self.text(m) in ("rt", "glm") and self.text(m + 1) == "::":
            return
        raise self.refuse(k, "using of rt's or GLM's names only", f"using {self.text(m)}",
                          "qualify the standard library's names with std:: where you use them")


def check(rel: str, toks: List[Token], partner: Dict[int, int]) -> None:
    """Raises Refused for the first token the allow-list does not take (see the module)."""
    rt = names.rt_names()
    walk = _Walk(toks, partner, ppm=rel == names.PPM_WRITER_FILE,
                 shadowing=rt.exercise_parameters.get(rel, frozenset()))
    walk.run()
