"""kits.strip - a kit's plan: which regions it strips and which it hands out
solved, the stub that replaces a stripped body, the switchable kit of
tools/check_kit.py (every region solved, stripped at run time by RT_KIT_STRIP),
and the files of tools/kit/ that replace the repository's README, DEVELOPERS.md
and CI script.
"""

from __future__ import annotations

import posixpath
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, Iterable, List, Optional, Set

from .regions import KitError, Region, stage_label
from .repository import (is_instructor_only, known_stages, load_manifest, repository_files, scan_repository,
                         stage_doc)

TOOLS_DIR = Path(__file__).resolve().parent.parent

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
