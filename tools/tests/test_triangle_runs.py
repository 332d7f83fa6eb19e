"""Tests of bench/triangle_runs.py: the triangle table of docs/performance.md from one
bench_triangle and bench_triangle_contract run, checked on a small run written by hand.

Run: python3 -m unittest -v test_triangle_runs   (ctest runs it as tools.triangle_runs)
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
import triangle_runs  # noqa: E402

HEADER = "mesh,triangles,rays,method,ray_count,seconds,mtests_per_s,ns_per_test,leaks,leak_fraction\n"


def write_csv(path: Path, flags: str, suffix: str):
    lines = [f"# machine: a test machine; {flags}\n", HEADER]
    for mesh, triangles in (("ico", 10), ("cone", 30)):
        for rays, leaks in (("surface", 0), ("edges", 5), ("vertices", 10)):
            # 100 rays x triangles tests in 0.001 s each
            lines.append(f"{mesh},{triangles},{rays},moller_trumbore{suffix},100,0.001,0,0,{leaks},0\n")
            lines.append(f"{mesh},{triangles},{rays},watertight{suffix},100,0.002,0,0,0,0\n")
    path.write_text("".join(lines))


class Table(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="triangle-runs-test-"))
        self.run = self.tmp / "run"
        self.run.mkdir()
        write_csv(self.run / "triangle.csv", "-ffp-contract=off", "")
        write_csv(self.run / "triangle_contract.csv", "-ffp-contract=fast", "+fma")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_leaks_of_both_meshes_together_and_the_speed_over_all_sets(self):
        text = triangle_runs.table(triangle_runs.load(str(self.run)))
        self.assertIn("Machine: a test machine; -ffp-contract=off.", text)
        self.assertIn("(bench_triangle_contract): a test machine; -ffp-contract=fast.", text)
        # 2 x 5 of 200 edge rays, 2 x 10 of 200 vertex rays; 100 x (10 + 30) x 3 tests in 0.006 s
        self.assertIn("| Moller-Trumbore | 0 / 200 | 10 / 200 (5.0%) | 20 / 200 (10.0%) | 2 |", text)
        self.assertIn("| watertight, `hit_triangle` | 0 / 200 | 0 / 200 | 0 / 200 | 1 |", text)
        self.assertIn("| Moller-Trumbore, FMA contraction | 0 / 200 | 10 / 200 (5.0%) |", text)
        self.assertIn("| watertight, `hit_triangle`, FMA contraction | 0 / 200 |", text)

    def test_the_marked_block_is_replaced_and_the_rest_kept(self):
        doc = self.tmp / "doc.md"
        doc.write_text(f"before\n{triangle_runs.BEGIN}\nold table\n{triangle_runs.END}\nafter\n")
        with contextlib.redirect_stdout(io.StringIO()):
            triangle_runs.main([str(self.run), "--doc", str(doc)])
        text = doc.read_text()
        self.assertTrue(text.startswith(f"before\n{triangle_runs.BEGIN}\nMachine: a test machine"))
        self.assertTrue(text.endswith(f"{triangle_runs.END}\nafter\n"))
        self.assertNotIn("old table", text)
        self.assertFalse(Path(str(doc) + ".tmp").exists())

    def test_an_interrupted_write_leaves_the_document_and_no_temporary_file(self):
        doc = self.tmp / "doc.md"
        doc.write_text(f"{triangle_runs.BEGIN}\nold table\n{triangle_runs.END}\n")
        import csv_notes  # noqa: E402 (beside triangle_runs.py)
        real_replace = csv_notes.os.replace

        def interrupted(*args):
            raise KeyboardInterrupt()
        csv_notes.os.replace = interrupted
        try:
            with self.assertRaises(KeyboardInterrupt):
                triangle_runs.main([str(self.run), "--doc", str(doc)])
        finally:
            csv_notes.os.replace = real_replace
        self.assertIn("old table", doc.read_text())
        self.assertFalse(Path(str(doc) + ".tmp").exists())

    def test_a_run_without_the_contract_program_is_refused_by_name(self):
        (self.run / "triangle_contract.csv").unlink()
        doc = self.tmp / "doc.md"
        doc.write_text(f"{triangle_runs.BEGIN}\nold table\n{triangle_runs.END}\n")
        with self.assertRaises(SystemExit) as caught:
            triangle_runs.main([str(self.run), "--doc", str(doc)])
        self.assertIn("triangle_contract.csv", str(caught.exception))
        self.assertIn("bench_triangle_contract", str(caught.exception))
        self.assertIn("old table", doc.read_text())


if __name__ == "__main__":
    unittest.main()
