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
import sys
from pathlib import Path
from typing import Iterable, List, Optional, Sequence

TOOLS_DIR = Path(__file__).resolve().parent
if str(TOOLS_DIR) not in sys.path:
    sys.path.insert(0, str(TOOLS_DIR))

# The package's names, also as make_kit.NAME: check_kit, the grader and the tests use them.
from kits.regions import (BEGIN_INSIDE_RE, BEGIN_RE, END_RE, HINT_RE, KitError, Region,  # noqa: E402,F401
                          _strip_template_prefix, parse_parameters, scan_file, stage_label)
from kits.repository import (ALWAYS_SKIPPED_DIRS, BUILD_DIR_RE, MANIFEST_NAME, SOURCE_SUFFIXES,  # noqa: E402,F401
                             STAGE_DOC_RE, STAGE_TEST_RE, exercise_files, is_instructor_only, known_stages,
                             load_manifest, repository_files, scan_repository, stage_doc)
from kits.strip import (KIT_CHECK_SWITCH, KIT_CHECK_SWITCH_FILE, KIT_REPLACEMENTS,  # noqa: E402,F401
                        KIT_STAGES_PLACEHOLDER, KitPlan, _error_header_include, _with_error_include, cxx_string,
                        not_done_message, plan_kit, select_stages, strip_text, stripped_body, switchable_body,
                        switchable_plan, switchable_text)
from kits.write import sync_kit, write_kit, write_tree  # noqa: E402,F401

DEFAULT_SOURCE = TOOLS_DIR.parent


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
