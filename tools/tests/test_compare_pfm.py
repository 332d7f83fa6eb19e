"""Tests of tools/compare_pfm.py: both byte orders, the grey form, the row order of
the pixel it names, the tolerance's edge, and one line for a file that is no PFM.

Run: python3 -m unittest discover -s tools/tests -v   (ctest runs it as tools.compare_pfm)
"""

import contextlib
import io
import struct
import sys
import tempfile
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(TOOLS))
import compare_pfm as cp  # noqa: E402


def pfm(path, width, height, values, little=True, grey=False):
    """Writes a PFM whose values are given in file order (rows bottom to top)."""
    order = "<" if little else ">"
    header = f"{'Pf' if grey else 'PF'}\n{width} {height}\n{-1.0 if little else 1.0}\n".encode()
    path.write_bytes(header + struct.pack(f"{order}{len(values)}f", *values))
    return path


class ComparePfm(unittest.TestCase):
    def setUp(self):
        self.folder = Path(tempfile.mkdtemp())

    def run_main(self, *args):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = cp.main([str(a) for a in args])
        return code, out.getvalue(), err.getvalue()

    def test_same_values_in_either_byte_order_pass(self):
        values = [0.5, 0.25, 1.0, 2.0, 0.0, 0.125]
        a = pfm(self.folder / "a.pfm", 2, 1, values, little=True)
        b = pfm(self.folder / "b.pfm", 2, 1, values, little=False)
        code, out, _ = self.run_main(a, b)
        self.assertEqual(code, 0)
        self.assertIn("0 differ", out)
        self.assertTrue(out.rstrip().endswith("compare_pfm: 1 passed, 0 failed"))

    def test_tolerance_edge_and_the_pixel_named_from_the_top(self):
        base = [0.5] * 12  # 2 x 2, rows bottom to top in the file
        near = list(base)
        near[0] += 0.5e-4  # the bottom-left pixel, red: within 1e-4
        far = list(base)
        far[4] += 3e-4  # value 4: the bottom row's second pixel (column 1, row 1 from the top), green
        a = pfm(self.folder / "a.pfm", 2, 2, base)
        code, out, _ = self.run_main(a, pfm(self.folder / "near.pfm", 2, 2, near), "--tolerance", "1e-4")
        self.assertEqual(code, 0, out)
        self.assertIn("1 differ, 0 by more than", out)
        code, out, _ = self.run_main(a, pfm(self.folder / "far.pfm", 2, 2, far), "--tolerance", "1e-4")
        self.assertEqual(code, 1, out)
        self.assertIn("1 by more than 0.0001", out)
        self.assertIn("at pixel (1, 1) channel 1", out)
        self.assertTrue(out.rstrip().endswith("compare_pfm: 0 passed, 1 failed"))

    def test_large_values_are_compared_relatively(self):
        a = pfm(self.folder / "a.pfm", 1, 1, [1000.0, 1.0, 1.0])
        b = pfm(self.folder / "b.pfm", 1, 1, [1000.05, 1.0, 1.0])  # 5e-5 relative
        self.assertEqual(self.run_main(a, b, "--tolerance", "1e-4")[0], 0)

    def test_sizes_must_match(self):
        a = pfm(self.folder / "a.pfm", 1, 1, [0.0, 0.0, 0.0])
        b = pfm(self.folder / "b.pfm", 1, 1, [0.0], grey=True)
        code, out, _ = self.run_main(a, b)
        self.assertEqual(code, 1)
        self.assertIn("expected images of one size", out)

    def test_a_file_that_is_not_a_pfm_is_one_line_and_exit_2(self):
        png = self.folder / "a.png"
        png.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(20))
        good = pfm(self.folder / "b.pfm", 1, 1, [0.0, 0.0, 0.0])
        code, out, err = self.run_main(png, good)
        self.assertEqual(code, 2)
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        self.assertIn("expected 'PF' or 'Pf'", err)
        short = self.folder / "short.pfm"
        short.write_bytes(b"PF\n2 2\n-1.0\n" + bytes(8))
        code, _, err = self.run_main(short, good)
        self.assertEqual(code, 2)
        self.assertIn("expected 48 bytes of pixels for 2 x 2, found 8", err)


if __name__ == "__main__":
    unittest.main()
