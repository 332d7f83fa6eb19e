#!/usr/bin/env python3
"""make_workflow.py - GitHub Classroom autograding for a student kit of rt.

    python3 tools/make_kit.py --from-stage 3 ../rt-week3
    python3 tools/classroom/make_workflow.py ../rt-week3 [--stages 3,4 or 3-5] [--weights tools/weights.json]

writes ../rt-week3/.github/workflows/classroom.yml: on every push, GitHub
Actions installs rt's build (Ubuntu's packages), configures the kit once, and
runs one graded step per stage, `cmake --build build --target check_stageNN`,
worth that stage's visible points in the weights file. GitHub Classroom's
command grader awards a step's points when its command exits 0 (all or
nothing: a stage passes when every one of its visible cases passes); the
reporter step adds them up for the Classroom's grade book
(classroom-resources/autograding-command-grader and
autograding-grading-reporter, v1).

The stages: --stages, or by default the stages the kit leaves to the students
(its stripped exercise regions). Only visible suites run: a kit holds no
hidden suite. The grading here is cumulative, the student's own code for
every stage, as on their machine; tools/grade.py judges each stage alone.

Exit code 0 when the workflow was written, 2 for a bad command line or a
folder that is not a kit. Python 3 standard library only.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Dict, List, Optional, Sequence

TOOLS_DIR = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(TOOLS_DIR))
import make_kit  # noqa: E402  (tools/make_kit.py)
from grading.common import GradeError, parse_stages  # noqa: E402  (the grader's: 3, 3,4 or 3-5)

WORKFLOW = Path(".github") / "workflows" / "classroom.yml"
GRADER = "classroom-resources/autograding-command-grader@v1"
REPORTER = "classroom-resources/autograding-grading-reporter@v1"
# Ubuntu's packages for rt's build (README.md's Debian and Ubuntu line)
INSTALL = ("sudo apt-get update && sudo apt-get install -y --no-install-recommends "
           "cmake ninja-build g++ libglm-dev doctest-dev libtinyobjloader-dev")
CONFIGURE = "cmake --preset default"
# A step builds its stage's suite and program before it runs them: the build
# is most of its time on a runner (2 cores), hence minutes beyond the tests' own.
BUILD_MINUTES = 10


class WorkflowError(Exception):
    """A one-line message: the workflow cannot be made (exit 2)."""


def stripped_stages(kit: Path) -> List[int]:
    """The stages whose exercise regions the kit leaves to the students: a
    stripped region holds make_kit's TODO(stage NN) line."""
    try:
        regions = make_kit.scan_repository(kit)
    except make_kit.KitError as e:
        raise WorkflowError(e.messages[0])
    stages = set()
    for region in regions:
        lines = (kit / region.path).read_text(encoding="utf-8").splitlines()
        body = lines[region.begin_line:region.end_line - 1]
        if any(f"TODO(stage {make_kit.stage_label(region.stage)})" in line for line in body):
            stages.add(region.stage)
    return sorted(stages)


def stage_title(kit: Path, stage: int) -> str:
    """'03 sphere' from docs/stages/03-sphere.md, or '03' without a page."""
    doc = make_kit.stage_doc(kit, stage)
    if doc is None:
        return make_kit.stage_label(stage)
    return Path(doc).stem.replace("-", " ", 1).replace("-", " ")


def load_weights(path: Path) -> Dict:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise WorkflowError(f"{path}: expected a readable weights file, found {e.strerror}; see --help")
    except json.JSONDecodeError as e:
        raise WorkflowError(f"{path}:{e.lineno}:{e.colno}: expected JSON, found {e.msg}")


def visible_points(weights: Dict, stage: int) -> float:
    entry = weights.get("stages", {}).get(make_kit.stage_label(stage), weights.get("default", {}))
    return float(entry.get("visible", weights.get("default", {}).get("visible", 10)))


def plan_steps(kit: Path, stages: Sequence[int], weights: Dict) -> List[Dict]:
    """The workflow's steps, in order: plain data, so that a test can run them."""
    timeout = BUILD_MINUTES + math.ceil(float(weights.get("stage_timeout_seconds", 120)) / 60)
    steps: List[Dict] = [
        {"name": "Check out the kit", "uses": "actions/checkout@v4"},
        {"name": "Install rt's build", "run": INSTALL},
        {"name": "Configure", "run": CONFIGURE},
    ]
    for stage in stages:
        label = make_kit.stage_label(stage)
        points = visible_points(weights, stage)
        steps.append({
            "name": f"Stage {stage_title(kit, stage)}",
            "id": f"stage-{label}",
            "uses": GRADER,
            "with": {
                "test-name": f"stage {stage_title(kit, stage)}",
                "command": f"cmake --build build --target check_stage{label}",
                "timeout": timeout,
                "max-score": int(points) if points == int(points) else points,
            },
        })
    ids = [s["id"] for s in steps if "id" in s]
    steps.append({
        "name": "Autograding reporter",
        "uses": REPORTER,
        "env": {f"{i.upper()}_RESULTS": f"${{{{ steps.{i}.outputs.result }}}}" for i in ids},
        "with": {"runners": ",".join(ids)},
    })
    return steps


def scalar(value) -> str:
    """A YAML scalar: numbers as they are, text double-quoted (JSON's escapes are YAML's)."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return str(value)
    return json.dumps(str(value), ensure_ascii=False)


def workflow_text(steps: List[Dict], stages: Sequence[int]) -> str:
    listed = ", ".join(make_kit.stage_label(s) for s in stages)
    out = [
        "# GitHub Classroom autograding, written by rt's tools/classroom/make_workflow.py:",
        f"# one graded step per stage ({listed}), `cmake --build build --target check_stageNN`,",
        "# worth the stage's points when every one of its tests passes.",
        "name: Autograding",
        "\"on\":",
        "  - push",
        "  - workflow_dispatch",
        "  - repository_dispatch",
        "permissions:",
        "  checks: write",
        "  actions: read",
        "  contents: read",
        "jobs:",
        "  autograding:",
        "    runs-on: ubuntu-24.04",
        "    if: github.actor != 'github-classroom[bot]'",
        "    steps:",
    ]
    for step in steps:
        first = True
        for key in ("name", "id", "uses", "run"):
            if key in step:
                out.append(("      - " if first else "        ") + f"{key}: {scalar(step[key])}")
                first = False
        for block in ("env", "with"):
            if block in step:
                out.append(f"        {block}:")
                for key, value in step[block].items():
                    out.append(f"          {key}: {scalar(value)}")
    return "\n".join(out) + "\n"


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        description="Write a kit's .github/workflows/classroom.yml for GitHub Classroom's autograding: "
                    "one graded step per stage, worth its visible points.")
    parser.add_argument("kit", type=Path, help="the kit's folder (tools/make_kit.py made it)")
    parser.add_argument("--stages",
                        help="the stages to grade, e.g. 3 or 3,4 or 3-5 (default: the stages the kit strips)")
    parser.add_argument("--weights", type=Path, default=TOOLS_DIR / "weights.json",
                        help="points per stage (default: tools/weights.json)")
    args = parser.parse_args(argv)
    try:
        kit = args.kit
        if not (kit / "CMakeLists.txt").is_file() or not (kit / "tests").is_dir():
            raise WorkflowError(f"{kit}: expected a kit of rt (CMakeLists.txt and tests/), found none; "
                                f"make one with tools/make_kit.py")
        known = sorted(make_kit.known_stages(kit))
        try:
            stages = parse_stages(args.stages, known) if args.stages else stripped_stages(kit)
        except GradeError as e:     # --stages 3, 3,4 or 3-5, as grade.py and make_autograder.py take
            raise WorkflowError(str(e))
        if not stages:
            raise WorkflowError(f"{kit}: expected a kit with stages to do, found every stage solved; "
                                f"name them with --stages")
        weights = load_weights(args.weights)
        text = workflow_text(plan_steps(kit, stages, weights), stages)
        target = kit / WORKFLOW
        target.parent.mkdir(parents=True, exist_ok=True)
        temporary = target.with_name(target.name + ".tmp")
        temporary.write_text(text, encoding="utf-8")
        temporary.replace(target)
    except WorkflowError as e:
        print(f"make_workflow: {e}", file=sys.stderr)
        return 2
    total = sum(visible_points(weights, s) for s in stages)
    print(f"make_workflow: wrote {target}: stages {', '.join(make_kit.stage_label(s) for s in stages)}, "
          f"{total:g} points")
    return 0


if __name__ == "__main__":
    sys.exit(main())
