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

from .splice import Composed, StudentRegion, compose, function_span

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

    def body(self) -> List[str]:
        """The region's body as a call into the other program."""
        names = [n for n, _ in self.region.parameters]
        arguments = "".join(f", {n}" for n in names)
        return [f"{self.region.indent}return ::rt::judge::call<{self.id}>({self.pointer(False)}{arguments});"]


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
    out = []
    for index, r in enumerate(reference.regions):
        template = template_parameters(reference.text(r.path).split("\n"), r) if r.path.startswith("include/") else []
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


def server_overlay(reference, stage: int, body_of, students: Dict[str, object]) -> Dict[str, Composed]:
    """The headers stage `stage`'s server compiles against: body_of(region) for the stage's
    own regions (the student's region, or "stub"), calls into the judge before it, the kit's
    stubs after it."""
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
                choice[k] = _remote(by_region[id(r)])
            else:
                choice[k] = "stub"
        files[rel] = compose(rel, reference.text(rel), regions, choice, reference.doc_of, students.get(rel))
    return files


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
