#!/usr/bin/env python3
"""compare_pfm.py - are two PFM images the same picture, channel by channel?

    python3 tools/compare_pfm.py linux.pfm windows.pfm --tolerance 1e-4

CI renders the showcase with the Linux build and with the Windows build (under
Wine) and compares the two here: every channel of every pixel must differ by at
most the tolerance (absolute, for values up to 1; relative above). It prints how
many channels differ at all, how many exceed the tolerance and the largest
difference, with the pixel (column, row from the top) where it is. The last line
reads "compare_pfm: 1 passed, 0 failed" or "... 0 passed, 1 failed"; exit 0 only
when it passed, 2 for a file that is not a PFM image (one line saying why).

PFM (Portable Float Map, Paul Debevec's format): a header "PF" (color) or "Pf"
(grey), the width and height, a scale whose sign gives the byte order (negative:
little-endian), then 32-bit floats, rows from the bottom up. Python 3 standard
library only.
"""

from __future__ import annotations

import argparse
import struct
import sys
from pathlib import Path
from typing import List, Optional, Sequence, Tuple


class PfmError(Exception):
    pass


def read_pfm(path: Path) -> Tuple[int, int, int, List[float]]:
    """(width, height, channels, values in file order: rows bottom to top)."""
    try:
        data = path.read_bytes()
    except OSError as e:
        raise PfmError(f"{path}: expected a readable PFM file, found {e.strerror or e}")
    if data[:2] not in (b"PF", b"Pf") or not data[2:3].isspace():
        raise PfmError(f"{path}: expected 'PF' or 'Pf' at the start, found {data[:8]!r}")
    words: List[bytes] = []
    position = 0
    while len(words) < 4:  # "PF", width, height, scale, each followed by one blank
        while position < len(data) and data[position:position + 1].isspace():
            position += 1
        start = position
        while position < len(data) and not data[position:position + 1].isspace():
            position += 1
        if start == position:
            raise PfmError(f"{path}: expected a PFM header (PF, width, height, scale), found the end of the file")
        words.append(data[start:position])
    position += 1  # the single blank after the scale
    kind, width_text, height_text, scale_text = words
    try:
        width, height, scale = int(width_text), int(height_text), float(scale_text)
    except ValueError:
        raise PfmError(f"{path}: expected a width, a height and a scale, found {b' '.join(words[1:])[:40]!r}")
    if width <= 0 or height <= 0 or scale == 0:
        raise PfmError(f"{path}: expected a positive size and a non-zero scale, found {width} x {height}, {scale}")
    channels = 3 if kind == b"PF" else 1
    count = width * height * channels
    if len(data) - position != 4 * count:
        raise PfmError(f"{path}: expected {4 * count} bytes of pixels for {width} x {height}, "
                       f"found {len(data) - position}")
    order = "<" if scale < 0 else ">"
    return width, height, channels, list(struct.unpack(f"{order}{count}f", data[position:]))


def compare(a: Path, b: Path, tolerance: float) -> Tuple[bool, str]:
    wa, ha, ca, va = read_pfm(a)
    wb, hb, cb, vb = read_pfm(b)
    if (wa, ha, ca) != (wb, hb, cb):
        return False, f"expected images of one size, found {wa} x {ha} x {ca} and {wb} x {hb} x {cb}"
    differing = over = 0
    largest, where = 0.0, 0
    for k, (x, y) in enumerate(zip(va, vb)):
        if x == y:
            continue
        differing += 1
        difference = abs(x - y) / max(1.0, abs(x), abs(y))
        over += difference > tolerance
        if difference > largest:
            largest, where = difference, k
    pixel = where // ca
    column, row = pixel % wa, ha - 1 - pixel // wa
    text = (f"{wa} x {ha} pixels, {len(va)} channels: {differing} differ, {over} by more than {tolerance:g}"
            + (f"; the largest difference {largest:.3g} at pixel ({column}, {row}) channel {where % ca}"
               if differing else ""))
    return over == 0, text


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("first", type=Path)
    parser.add_argument("second", type=Path)
    parser.add_argument("--tolerance", type=float, default=1e-4,
                        help="largest difference allowed per channel (absolute up to 1, relative above)")
    args = parser.parse_args(argv)
    try:
        ok, text = compare(args.first, args.second, args.tolerance)
    except PfmError as e:
        print(f"compare_pfm: {e}", file=sys.stderr)
        return 2
    print(f"compare_pfm: {text}")
    print(f"compare_pfm: {1 if ok else 0} passed, {0 if ok else 1} failed")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
