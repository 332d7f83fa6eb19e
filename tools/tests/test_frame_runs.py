"""Tests of bench/frame_runs.py: the whole-frame table of docs/performance.md from two
bench_frame runs, checked on two small runs written by hand.

Run: python3 -m unittest -v test_frame_runs   (ctest runs it as tools.frame_runs)
"""

import contextlib
import io
import shutil
import sys
import tempfile
import unittest
from pathlib import Path

BENCH = Path(__file__).resolve().parent.parent.parent / "bench"
sys.path.insert(0, str(BENCH))
import frame_runs  # noqa: E402

HEADER = ("scene,width,height,threads,build_seconds,seconds,camera_rays,shadow_rays,reflection_rays,"
          "mrays_per_s,speedup\n")


def write_run(folder: Path, one: float, two: float, threads=(1, 2)):
    folder.mkdir(parents=True)
    lines = ["# machine: a test machine\n", "# render: 64x48, 1 spp\n", HEADER]
    for t in threads:
        seconds = one if t == 1 else two
        lines.append(f"cube.obj,64,48,{t},0.002,{seconds},3072,1000,500,{4572 / seconds / 1e6},{one / seconds}\n")
    (folder / "frame.csv").write_text("".join(lines))


class Table(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="frame-runs-test-"))
        write_run(self.tmp / "one", 0.010, 0.005)
        write_run(self.tmp / "two", 0.012, 0.004)

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_each_timing_of_the_first_run_then_the_second_in_brackets(self):
        text = frame_runs.table(frame_runs.load(self.tmp / "one"), frame_runs.load(self.tmp / "two"))
        self.assertIn("Machine: a test machine.", text)
        self.assertIn("| scene | 1 thread (s) | 2 threads (s) | speed-up |", text)
        # 0.010 s and 0.005 s: 2.00x; 0.012 s and 0.004 s: 3.00x; 4572 rays in 0.010 s: 0.46 Mrays/s
        self.assertIn("| cube (64x48) | 0.010 (0.012) | 0.005 (0.004) | 2.00x (3.00x) | 3072 | 1000 | 500 "
                      "| 0.5 (0.4) | 0.002 (0.002) |", text)

    def test_the_marked_block_is_replaced_and_the_rest_kept(self):
        doc = self.tmp / "doc.md"
        doc.write_text(f"before\n{frame_runs.BEGIN}\nold table\n{frame_runs.END}\nafter\n")
        with contextlib.redirect_stdout(io.StringIO()):
            frame_runs.main([str(self.tmp / "one"), str(self.tmp / "two"), "--doc", str(doc)])
        text = doc.read_text()
        self.assertTrue(text.startswith(f"before\n{frame_runs.BEGIN}\nMachine: a test machine."))
        self.assertTrue(text.endswith(f"{frame_runs.END}\nafter\n"))
        self.assertNotIn("old table", text)
        self.assertFalse(Path(str(doc) + ".tmp").exists())

    def test_a_document_without_the_markers_is_left_as_it_was(self):
        doc = self.tmp / "doc.md"
        doc.write_text("no markers here\n")
        with self.assertRaises(SystemExit) as caught:
            frame_runs.main([str(self.tmp / "one"), str(self.tmp / "two"), "--doc", str(doc)])
        self.assertIn("expected one '<!-- frame-runs:begin -->' line", str(caught.exception))
        self.assertEqual(doc.read_text(), "no markers here\n")

    def test_a_run_on_one_thread_only_is_refused(self):
        write_run(self.tmp / "single", 0.010, 0.010, threads=(1,))
        with self.assertRaises(SystemExit) as caught:
            frame_runs.table(frame_runs.load(self.tmp / "single"), frame_runs.load(self.tmp / "two"))
        self.assertIn("2 threads or more", str(caught.exception))


EMBREE_HEADER = ("scene,width,height,spp,threads,rt_build_seconds,rt_frame_seconds,embree_build_seconds,"
                 "embree_frame_seconds,ratio_rt_over_embree,mean_difference,rt_plain_build_seconds,rt_plain_frame_seconds\n")


def write_embree_run(folder: Path, rt_frame: float, embree_frame: float, spps=(1, 16)):
    folder.mkdir(parents=True, exist_ok=True)
    lines = ["# machine: a test machine\n", "# render: 128x72\n", EMBREE_HEADER]
    for spp in spps:
        ratio = (0.5 + rt_frame * spp) / (0.25 + embree_frame * spp)
        lines.append(f"cube.obj,128,72,{spp},2,0.5,{rt_frame * spp},0.25,{embree_frame * spp},{ratio},3e-09,0.4,{rt_frame * spp * 1.2}\n")
    (folder / "frame_embree.csv").write_text("".join(lines))


class EmbreeTable(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="frame-runs-test-"))

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_build_and_frame_of_each_engine_then_the_second_run_in_brackets(self):
        write_embree_run(self.tmp / "one", 0.1, 0.2)
        write_embree_run(self.tmp / "two", 0.1, 0.1)
        text = frame_runs.table_embree(frame_runs.load_embree(self.tmp / "one"),
                                       frame_runs.load_embree(self.tmp / "two"))
        self.assertIn("| scene | spp | rt: build + frame (s) | Embree: build + frame (s) | rt / Embree |", text)
        # 16 spp: rt 0.5 + 1.6 s, Embree 0.25 + 3.2 s (first run) or 0.25 + 1.6 s (second): 0.61 and 1.14;
        # rt without splits 0.4 + 1.92 s: the splits take 2.1 / 2.32 = 0.91 of its time
        self.assertIn("| cube (128x72) | 16 | 0.500 + 1.600 (0.500 + 1.600) | 0.250 + 3.200 (0.250 + 1.600) "
                      "| 0.61 (1.14) | 3.0e-09 | 0.400 + 1.920 (0.400 + 1.920) | 0.91 (0.91) |", text)

    def test_a_sample_count_missing_from_one_run_is_named(self):
        write_embree_run(self.tmp / "one", 0.1, 0.2)
        write_embree_run(self.tmp / "two", 0.1, 0.1, spps=(1,))
        with self.assertRaises(SystemExit) as caught:
            frame_runs.table_embree(frame_runs.load_embree(self.tmp / "one"),
                                    frame_runs.load_embree(self.tmp / "two"))
        self.assertIn("cube (16 spp) in the first only", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
