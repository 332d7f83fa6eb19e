"""Tests of tools/classroom/make_workflow.py: the GitHub Classroom workflow of a kit.

The workflow is read back as GitHub would read it (YAML), and its configure
step and a stage's graded command are run in two kits made from this
repository: one with every exercise finished (the reference's own bodies),
where the step passes, and one with stage 03 on, where it fails with the exercise's not-done message.

Run: python3 -m unittest -v test_classroom   (ctest runs it as tools.classroom)
"""

import contextlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))
sys.path.insert(0, str(TOOLS / "classroom"))
import make_kit  # noqa: E402
import make_workflow  # noqa: E402


def read_workflow(text):
    """The steps of a workflow: with PyYAML where it is installed, else a reader of
    the block form make_workflow writes (keys, double-quoted or numeric values)."""
    try:
        import yaml  # noqa: PLC0415
        return yaml.safe_load(text)["jobs"]["autograding"]["steps"]
    except ImportError:
        pass
    steps, block = [], None
    for line in text.splitlines():
        m = re.match(r"^( *)(- )?([\w-]+): ?(.*)$", line)
        if not m or len(m.group(1)) < 6:
            continue
        indent, dash, key, value = len(m.group(1)), m.group(2), m.group(3), m.group(4)
        if dash:
            steps.append({})
            block = None
        if value == "":
            block = key
            steps[-1][key] = {}
        elif indent >= 10 and block:
            steps[-1][block][key] = json.loads(value)
        else:
            steps[-1][key] = json.loads(value)
    return steps


def make(kit, stages):
    plan = make_kit.plan_kit(REPO, set(stages))
    make_kit.write_kit(REPO, plan, kit)


def workflow(kit, *arguments):
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out):
        code = make_workflow.main([str(kit), *arguments])
    return code, out.getvalue()


def run(command, kit):
    return subprocess.run(command, shell=True, cwd=kit, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=900)


class ClassroomWorkflow(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scratch = Path(tempfile.mkdtemp(prefix="rt-classroom-"))
        cls.stages = sorted(make_kit.known_stages(REPO))
        cls.finished = cls.scratch / "finished"
        cls.stripped = cls.scratch / "week3"
        make(cls.finished, [])
        make(cls.stripped, [s for s in cls.stages if s >= 3])

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.scratch, ignore_errors=True)

    def test_default_stages_are_the_ones_the_kit_strips(self):
        code, out = workflow(self.stripped)
        self.assertEqual(code, 0, out)
        steps = read_workflow((self.stripped / make_workflow.WORKFLOW).read_text(encoding="utf-8"))
        graded = [s for s in steps if s.get("uses") == make_workflow.GRADER]
        self.assertEqual([s["with"]["command"] for s in graded],
                         [f"cmake --build build --target check_stage{s:02d}" for s in self.stages if s >= 3])
        weights = json.loads((TOOLS / "weights.json").read_text(encoding="utf-8"))
        for step, stage in zip(graded, [s for s in self.stages if s >= 3]):
            self.assertEqual(step["with"]["max-score"], weights["stages"][f"{stage:02d}"]["visible"],
                             f"stage {stage:02d}: expected its visible points from tools/weights.json")
        reporter = steps[-1]
        self.assertEqual(reporter["uses"], make_workflow.REPORTER)
        self.assertEqual(reporter["with"]["runners"].split(","), [s["id"] for s in graded])
        for step in graded:  # the reporter reads each step's result under its id, upper case
            self.assertEqual(reporter["env"][step["id"].upper() + "_RESULTS"],
                             "${{ steps." + step["id"] + ".outputs.result }}")

    def test_a_finished_kit_has_no_stage_to_grade_unless_named(self):
        code, out = workflow(self.finished)
        self.assertEqual(code, 2)
        self.assertIn("expected a kit with stages to do, found every stage solved; name them with --stages", out)
        code, out = workflow(self.finished, "--stages", "3,99")
        self.assertEqual(code, 2)
        self.assertIn("found 99", out)
        code, out = workflow(self.finished, "--stages", "three")
        self.assertEqual(code, 2)
        self.assertIn('--stages three: expected stage numbers such as 3 or 3,4 or 3-5, found "three"', out)
        code, out = workflow(self.finished, "--stages", "3-4")     # a range, as grade.py takes
        self.assertEqual(code, 0, out)
        steps = read_workflow((self.finished / make_workflow.WORKFLOW).read_text(encoding="utf-8"))
        self.assertEqual([s["id"] for s in steps if "id" in s], ["stage-03", "stage-04"])

    def test_steps_pass_on_a_finished_kit_and_fail_on_a_stripped_one(self):
        results = {}
        for kit in (self.finished, self.stripped):
            code, out = workflow(kit, "--stages", "3")
            self.assertEqual(code, 0, out)
            steps = read_workflow((kit / make_workflow.WORKFLOW).read_text(encoding="utf-8"))
            for step in steps:  # the install step needs root and the network: CI has installed those packages
                if "run" in step and "apt-get" not in step["run"]:
                    done = run(step["run"], kit)
                    self.assertEqual(done.returncode, 0, f"{step['run']} in {kit.name}:\n{done.stdout[-3000:]}")
            graded = [s for s in steps if s.get("uses") == make_workflow.GRADER]
            self.assertEqual(len(graded), 1)
            results[kit.name] = run(graded[0]["with"]["command"], kit)
        self.assertEqual(results["finished"].returncode, 0,
                         "a finished kit: expected check_stage03 to pass, found:\n" + results["finished"].stdout[-3000:])
        self.assertNotEqual(results["week3"].returncode, 0,
                            "a kit with stage 03 stripped: expected check_stage03 to fail, found it passed")
        self.assertRegex(results["week3"].stdout, r"stage 03: [^\n]*: see docs/stages/03-sphere\.md",
                         "expected the stripped exercise's not-done message")


if __name__ == "__main__":
    unittest.main()
