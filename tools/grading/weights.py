"""The weights file: the points of each stage's visible and hidden suites and the time
limits (docs/instructor-guide.md, "Weights")."""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict

from .common import GradeError

VISIBILITIES = ("hidden", "after_due_date", "after_published", "visible")


@dataclass
class Weights:
    stage_timeout: float = 120        # the run time of a stage's cases, together
    case_timeout: float = 60          # of one case
    compile_timeout: float = 120      # of the build of a stage's server
    hidden_visibility: str = "after_published"
    default_visible: float = 10
    default_hidden: float = 0
    stages: Dict[int, Dict[str, float]] = field(default_factory=dict)

    def points(self, stage: int, suite: str) -> float:
        entry = self.stages.get(stage, {})
        return float(entry.get(suite, self.default_visible if suite == "visible" else self.default_hidden))


def load_weights(path: Path) -> Weights:
    where = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise GradeError(f"{where}: expected a readable weights file, found {e.strerror}; "
                         f"see docs/instructor-guide.md")
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise GradeError(f"{where}:{e.lineno}:{e.colno}: expected JSON, found {e.msg}")

    def fail(key: str, expected: str, found: object) -> GradeError:
        line = next((k + 1 for k, l in enumerate(text.splitlines()) if f'"{key}"' in l), 1)
        return GradeError(f"{where}:{line}: expected {expected} for \"{key}\", found {json.dumps(found)}")

    def number(key: str, value: object) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0:
            raise fail(key, "a number >= 0", value)
        return float(value)

    if not isinstance(data, dict):
        raise GradeError(f"{where}:1:1: expected a JSON object, found {type(data).__name__}")
    w = Weights()
    known = {"stage_timeout_seconds", "case_timeout_seconds", "compile_timeout_seconds", "hidden_visibility",
             "default", "stages"}
    for key in data:
        if key not in known and not key.startswith("//"):
            raise fail(key, "one of " + ", ".join(sorted(known)) + " (or a \"//\" comment)", key)
    if "stage_timeout_seconds" in data:
        w.stage_timeout = number("stage_timeout_seconds", data["stage_timeout_seconds"])
    if "case_timeout_seconds" in data:
        w.case_timeout = number("case_timeout_seconds", data["case_timeout_seconds"])
    if "compile_timeout_seconds" in data:
        w.compile_timeout = number("compile_timeout_seconds", data["compile_timeout_seconds"])
    if "hidden_visibility" in data:
        if data["hidden_visibility"] not in VISIBILITIES:
            raise fail("hidden_visibility", "one of " + ", ".join(VISIBILITIES), data["hidden_visibility"])
        w.hidden_visibility = data["hidden_visibility"]

    def suite_points(key: str, entry: object) -> Dict[str, float]:
        if not isinstance(entry, dict):
            raise fail(key, '{"visible": points, "hidden": points}', entry)
        out = {}
        for suite, value in entry.items():
            if suite.startswith("//"):
                continue
            if suite not in ("visible", "hidden"):
                raise fail(key, '"visible" or "hidden"', suite)
            out[suite] = number(key, value)
        return out

    if "default" in data:
        d = suite_points("default", data["default"])
        w.default_visible = d.get("visible", w.default_visible)
        w.default_hidden = d.get("hidden", w.default_hidden)
    stages = data.get("stages", {})
    if not isinstance(stages, dict):
        raise fail("stages", 'an object {"01": {...}, ...}', stages)
    for key, entry in stages.items():
        if key.startswith("//"):
            continue
        if not re.fullmatch(r"[0-9]{2}", key):
            raise fail(key, "a two-digit stage such as \"03\"", key)
        w.stages[int(key)] = suite_points(key, entry)
    return w
