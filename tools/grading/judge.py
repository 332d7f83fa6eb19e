"""The judge and the student's server: the sources tools/grading/judge/ builds from, written
for each stage (tools/grading/judge/README.md).

Every region of the reference has a number: its index in Reference.regions. Stage N's
judge is its suites built against headers in which stage N's bodies are calls into the
server, `return ::rt::judge::call<ID>(&::rt::f, a, b);`, and a table of the functions the
judge serves: the reference's of every other stage. Stage N's server is server.cpp built
against headers in which stage N's bodies are the student's, the stages before N are calls
back into the judge (so no reference body is compiled into it) and the stages after N are
the kit's stubs, with a table of stage N's functions.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional

import sys

from .common import GradeError
from .splice import Composed, StudentRegion, compose, function_span

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
import make_kit  # noqa: E402  (tools/make_kit.py: the kit's bodies)

JUDGE_SOURCES = Path(__file__).resolve().parent / "judge"

# The stand-in each template parameter of an exercise is served as (remote.hpp).
STAND_INS = {"Accelerator": "::rt::judge::remote_accelerator", "HitItem": "::rt::judge::remote_hit_item"}


@dataclass
class Exercise:
    id: int
    region: object          # make_kit.Region
    template: List[str]     # the function's template parameters, by name

    def pointer(self, served: bool) -> str:
        """&::rt::f or &::rt::f<T>: as the body names it (the template's own parameters),
        or as a table serves it (the stand-ins)."""
        name = f"::rt::{self.region.function}"
        if not self.template:
            return f"&{name}"
        args = [STAND_INS.get(t, t) if served else t for t in self.template]
        return f"&{name}<{', '.join(args)}>"

    def call(self) -> str:
        """The statement that calls the function in the other program."""
        arguments = "".join(f", {n}" for n, _ in self.region.parameters)
        return f"return ::rt::judge::call<{self.id}>({self.pointer(False)}{arguments});"

    def body(self) -> List[str]:
        """The region's body as a call into the other program."""
        return [self.region.indent + self.call()]


def template_parameters(lines: List[str], region) -> List[str]:
    """The names of the template parameters of the region's function ([] when it is none)."""
    span = function_span(lines, region)
    if span is None:
        return []
    for idx in range(span[0], max(span[0] - 8, -1), -1):
        code = lines[idx].split("//")[0]
        m = re.search(r"\btemplate\s*<(.*)>", code)
        if m:
            names = []
            for part in m.group(1).split(","):
                w = re.findall(r"[A-Za-z_]\w*", part.split("=")[0])
                if w:
                    names.append(w[-1])
            return names
        if idx < span[0] and code.rstrip().endswith((";", "}")):
            break
    return []


def exercises(reference) -> List[Exercise]:
    """Every region as an exercise the judge can call. A template's calls cross from one
    program to the other, so each of its parameters must have a stand-in the two agree on."""
    out = []
    for index, r in enumerate(reference.regions):
        template = template_parameters(reference.text(r.path).split("\n"), r) if r.path.startswith("include/") else []
        unknown = [t for t in template if t not in STAND_INS]
        if unknown:
            raise GradeError(f"{r.path}:{r.begin_line}: expected an exercise that is a function, or a template over "
                             f"{' or '.join(sorted(STAND_INS))} (the judge serves those by stand-ins), found a "
                             f"template over {', '.join(unknown)}; make the exercise a function of concrete types, "
                             f"or add a stand-in to STAND_INS in tools/grading/judge.py")
        out.append(Exercise(index, r, template))
    return out


def _remote(ex: Exercise) -> StudentRegion:
    return StudentRegion(ex.region.stage, ex.region.title, 0, 0, ex.body())


def judge_overlay(reference, stage: int) -> Dict[str, Composed]:
    """The headers stage `stage`'s judge compiles against: its bodies call the server,
    every other stage's are the reference's."""
    by_region = {id(e.region): e for e in exercises(reference)}
    files = {}
    for rel, regions in reference.by_file.items():
        if not rel.startswith("include/"):
            continue
        choice = {k: (_remote(by_region[id(r)]) if r.stage == stage else "reference") for k, r in enumerate(regions)}
        files[rel] = compose(rel, reference.text(rel), regions, choice, reference.doc_of, None)
    return files


def server_overlay(reference, stage: int, body_of, students: Dict[str, object],
                   cumulative: bool = False) -> Dict[str, Composed]:
    """The headers stage `stage`'s server compiles against: body_of(region) for the stage's
    own regions (the student's region, or "stub"), calls into the judge before it (or, when
    `cumulative`, body_of as well), the kit's stubs after it."""
    by_region = {id(e.region): e for e in exercises(reference)}
    files = {}
    for rel, regions in reference.by_file.items():
        if not rel.startswith("include/"):
            continue
        choice = {}
        for k, r in enumerate(regions):
            if r.stage == stage:
                choice[k] = body_of(r)
            elif r.stage < stage:
                choice[k] = body_of(r) if cumulative else _remote(by_region[id(r)])
            else:
                choice[k] = "stub"
        files[rel] = compose(rel, reference.text(rel), regions, choice, reference.doc_of, students.get(rel))
    return files


def group_overlay(reference, stages: List[int], body_of, students: Dict[str, object],
                  cumulative: bool = False) -> Dict[str, Composed]:
    """The headers of one server for several stages (`stages`, ascending): the server is
    told the stage it serves (serving_stage(), from the judge), and each region of a stage
    S from the first to the last of them starts with one line that makes it what S's own
    server would have: the student's body when S is served, a call back into the judge when
    a later stage is (the reference's answer; the student's body when `cumulative`), the
    kit's not-done when an earlier one is. Regions before the first stage are calls into
    the judge (or the student's, when `cumulative`), after the last the kit's stubs. One
    build instead of one per stage: the headers are parsed once."""
    by_region = {id(e.region): e for e in exercises(reference)}
    first, last = stages[0], stages[-1]
    files = {}
    for rel, regions in reference.by_file.items():
        if not rel.startswith("include/"):
            continue
        choice: Dict[int, object] = {}
        for k, r in enumerate(regions):
            if r.stage > last:
                choice[k] = "stub"
            elif r.stage < first:
                choice[k] = body_of(r) if cumulative else _remote(by_region[id(r)])
            else:
                choice[k] = _dispatched(by_region[id(r)], body_of(r), reference.doc_of.get(r.stage), cumulative)
        files[rel] = compose(rel, reference.text(rel), regions, choice, reference.doc_of, students.get(rel))
    return files


def _dispatched(e: Exercise, chosen: object, doc: Optional[str], cumulative: bool) -> StudentRegion:
    """The region's body (the student's StudentRegion, or "stub") after a line that sends
    the calls of another served stage elsewhere. The line stands for the BEGIN marker's, so
    the student's lines keep their numbers."""
    r = e.region
    stage = "::rt::judge::serving_stage()"
    not_done = f"throw ::rt::exercise_not_done({make_kit.cxx_string(make_kit.not_done_message(r, doc))});"
    if cumulative:
        line = f"{r.indent}if ({stage} < {r.stage}) {not_done}"
    else:
        line = f"{r.indent}if ({stage} != {r.stage}) {{ if ({stage} > {r.stage}) {e.call()} {not_done} }}"
    if isinstance(chosen, StudentRegion):
        return StudentRegion(r.stage, r.title, chosen.begin_line - 1, chosen.end_line, [line] + list(chosen.body))
    return StudentRegion(r.stage, r.title, -1, 0, [line] + make_kit.stripped_body(r, doc))


def group_table(reference, stages: List[int]) -> str:
    """judge_table.hpp of a server for `stages`: the functions of every stage it holds."""
    chosen = [e for e in exercises(reference) if stages[0] <= e.region.stage <= stages[-1]
              and e.region.path.startswith("include/")]
    includes = sorted({e.region.path for e in chosen})
    return ("// Written by tools/grading/judge.py: the functions a server of stages %s runs.\n#pragma once\n"
            % ", ".join(f"{s:02d}" for s in stages) + '#include "remote.hpp"\n' + _table(reference, chosen, includes))


def _table(reference, chosen: List[Exercise], includes: List[str]) -> str:
    lines = [f"#include <{rel[len('include/'):]}>" for rel in includes]
    lines.append("")
    lines.append("void rt_judge_table(::rt::judge::peer& to)")
    lines.append("{")
    lines += [f"    to.add({e.id}, {e.pointer(True)}); // {e.region.path}: stage{e.region.stage:02d}: {e.region.title}"
              for e in chosen]
    if not chosen:
        lines.append("    (void)to;")
    lines.append("}")
    return "\n".join(lines) + "\n"


def judge_table(reference, stage: int) -> str:
    """judge_table.cpp of stage `stage`'s judge: the reference's functions of every other stage."""
    chosen = [e for e in exercises(reference) if e.region.stage != stage and e.region.path.startswith("include/")]
    includes = sorted({e.region.path for e in chosen})
    return ("// Written by tools/grading/judge.py: what stage %02d's judge serves its server.\n" % stage +
            '#include "judge.hpp"\n' + _table(reference, chosen, includes))


def server_table(reference, stage: int) -> str:
    """judge_table.hpp of stage `stage`'s server: the stage's functions."""
    chosen = [e for e in exercises(reference) if e.region.stage == stage and e.region.path.startswith("include/")]
    includes = sorted({e.region.path for e in chosen})
    return ("// Written by tools/grading/judge.py: the functions stage %02d's server runs.\n#pragma once\n" % stage +
            '#include "remote.hpp"\n' + _table(reference, chosen, includes))


def stage_of_target(name: str) -> Optional[int]:
    m = re.match(r"test_(?:hidden_)?stage([0-9]{2})_", name)
    return int(m.group(1)) if m else None
