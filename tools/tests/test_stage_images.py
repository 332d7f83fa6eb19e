"""Tests of tools/stage_images.py: the PNG decoder (every filter, against the spec's Paeth),
the comparison, the crop, the table against the pages, and --update's refusals.

Run: python3 -m unittest discover -s tools/tests -v   (ctest runs it as tools.stage_images)
"""

import struct
import sys
import tempfile
import unittest
import zlib
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))
import stage_images as si  # noqa: E402


def paeth(a, b, c):
    """The predictor exactly as the PNG spec (sec. 9.4) writes it, apart from the decoder's."""
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    if pb <= pc:
        return b
    return c


def encode(width, height, channels, pixels, filters):
    """A PNG whose row y is written with filter filters[y % len(filters)] (the encoder's side)."""
    stride = width * channels
    raw = bytearray()
    previous = bytes(stride)
    for y in range(height):
        row = pixels[y * stride:(y + 1) * stride]
        kind = filters[y % len(filters)]
        out = bytearray()
        for x in range(stride):
            a = row[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            predictor = [0, a, b, (a + b) // 2, paeth(a, b, c)][kind]
            out.append((row[x] - predictor) & 0xFF)
        raw += bytes([kind]) + out
        previous = row
    color = {1: 0, 2: 4, 3: 2, 4: 6}[channels]

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    return (si.PNG_SIGNATURE + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, color, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(bytes(raw))) + chunk(b"IEND", b""))


def noise(n, seed=1):
    """n bytes of a fixed pseudo-random sequence (a 32-bit LCG, high byte)."""
    out = bytearray()
    x = seed
    for _ in range(n):
        x = (1664525 * x + 1013904223) & 0xFFFFFFFF
        out.append(x >> 24)
    return bytes(out)


class Decoding(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.dir = Path(self.folder.name)

    def tearDown(self):
        self.folder.cleanup()

    def decode(self, data):
        path = self.dir / "x.png"
        path.write_bytes(data)
        return si.read_png(path)

    def test_every_filter_and_channel_count_decodes_to_the_pixels_encoded(self):
        for channels in (1, 2, 3, 4):
            for filters in ([0], [1], [2], [3], [4], [4, 3, 2, 1, 0]):
                with self.subTest(channels=channels, filters=filters):
                    width, height = 7, 6
                    pixels = noise(width * height * channels, seed=channels)
                    picture = self.decode(encode(width, height, channels, pixels, filters))
                    self.assertEqual((picture.width, picture.height, picture.channels), (width, height, channels))
                    self.assertEqual(picture.data, pixels)

    def test_what_write_png_writes_reads_back(self):
        picture = si.Picture(5, 3, 3, noise(45))
        si.write_png(self.dir / "w.png", picture)
        self.assertEqual(si.read_png(self.dir / "w.png").data, picture.data)

    def test_a_file_that_is_not_a_png_is_one_line_naming_it(self):
        path = self.dir / "y.png"
        path.write_bytes(b"P6\n1 1\n255\n\0\0\0")
        with self.assertRaises(si.BadInput) as e:
            si.read_png(path, "docs/images/y.png")
        self.assertRegex(str(e.exception), r"^docs/images/y\.png:1:1: expected the PNG signature, found .*; hint: ")
        self.assertNotIn("\n", str(e.exception))

    def test_a_16_bit_png_is_refused(self):
        data = bytearray(encode(2, 2, 3, noise(12), [0]))
        data[24] = 16  # IHDR bit depth (its CRC is not checked)
        with self.assertRaises(si.BadInput) as e:
            self.decode(bytes(data))
        self.assertIn("expected an 8-bit, non-interlaced grey or RGB(A) PNG, found bit depth 16", str(e.exception))

    def test_a_bad_filter_byte_is_refused(self):
        raw = b"\x05" + bytes(3)
        body = struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)
        data = (si.PNG_SIGNATURE + struct.pack(">I", 13) + b"IHDR" + body + bytes(4)
                + struct.pack(">I", len(zlib.compress(raw))) + b"IDAT" + zlib.compress(raw) + bytes(4))
        with self.assertRaises(si.BadInput) as e:
            self.decode(data)
        self.assertIn("expected a row filter 0-4, found 5 in row 0", str(e.exception))


class Comparing(unittest.TestCase):
    def test_counts_the_pixels_that_differ_and_the_largest_channel_difference(self):
        a = si.Picture(3, 1, 3, bytes([10, 20, 30, 40, 50, 60, 70, 80, 90]))
        b = si.Picture(3, 1, 3, bytes([10, 20, 30, 41, 50, 60, 70, 80, 57]))
        d = si.compare(a, b)
        self.assertEqual((d.pixels, d.largest, d.total), (2, 33, 3))
        self.assertFalse(d.equal)
        self.assertIn("2 of 3 pixels differ", str(d))
        self.assertIn("largest channel difference 33", str(d))

    def test_equal_pictures_are_equal(self):
        a = si.Picture(2, 2, 1, bytes([1, 2, 3, 4]))
        self.assertTrue(si.compare(a, si.Picture(2, 2, 1, bytes([1, 2, 3, 4]))).equal)

    def test_a_different_size_is_never_equal(self):
        d = si.compare(si.Picture(2, 1, 1, bytes(2)), si.Picture(1, 2, 1, bytes(2)))
        self.assertFalse(d.equal)
        self.assertEqual(str(d), "size 2x1, committed 1x2")

    def test_magnify_makes_each_pixel_a_block(self):
        picture = si.Picture(3, 2, 1, bytes([1, 2, 3, 4, 5, 6]))
        big = si.magnify(picture, 1, 0, 2, 2, 2)
        self.assertEqual((big.width, big.height), (4, 4))
        self.assertEqual(big.data, bytes([2, 2, 3, 3, 2, 2, 3, 3, 5, 5, 6, 6, 5, 5, 6, 6]))


class Table(unittest.TestCase):
    def test_every_picture_of_the_pages_has_its_command(self):
        self.assertEqual(si.unmade_pictures(REPO), [])
        self.assertGreater(len(si.pictures_of_pages(REPO)), 20)

    def test_a_picture_without_a_command_is_named_with_its_page_and_line(self):
        with tempfile.TemporaryDirectory() as folder:
            root = Path(folder)
            (root / "docs/stages").mkdir(parents=True)
            (root / "docs/stages/11-new.md").write_text("# new\n\nText ![new](../images/11-new.png)\n"
                                                       "![viewer](../images/viewer-x.png)\n")
            (root / "README.md").write_text("![the default scene](docs/images/showcase.png)\n")
            self.assertEqual(si.unmade_pictures(root), [
                "docs/stages/11-new.md:3:23: expected a picture tools/stage_images.py makes, found 11-new.png; "
                "hint: add the command that makes it to IMAGES in tools/stage_images.py"])

    def test_every_image_is_made_once_and_is_committed(self):
        made = [i for r in si.IMAGES for i in r.images]
        self.assertEqual(len(made), len(set(made)))
        for image in made:
            self.assertTrue((REPO / "docs/images" / image).is_file(), image)

    def test_the_table_paths_exist(self):
        for render in si.IMAGES:
            for arg in render.args:
                if arg.startswith("scenes/"):
                    self.assertTrue((REPO / arg).is_file(), arg)

    def test_each_planted_line_is_in_its_file_once(self):
        for render in si.IMAGES:
            if render.plant:
                text = (REPO / render.plant.path).read_text()
                self.assertEqual(text.count(render.plant.old), 1, render.plant.old)


class CommandLine(unittest.TestCase):
    def test_out_may_not_be_docs_images(self):
        with self.assertRaises(SystemExit) as e:
            si.main(["--out", str(REPO / "docs/images"), "--build", "/nonexistent"])
        self.assertEqual(e.exception.code, 2)

    def test_update_changes_nothing_when_a_render_fails(self):
        with tempfile.TemporaryDirectory() as folder:
            before = (REPO / "docs/images/05-shading.png").read_bytes()
            code = si.main(["--programs", folder, "--out", folder, "--only", "05-shading.png", "--update"])
            self.assertEqual(code, 1)
            self.assertEqual((REPO / "docs/images/05-shading.png").read_bytes(), before)


if __name__ == "__main__":
    unittest.main()
