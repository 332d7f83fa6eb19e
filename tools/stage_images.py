#!/usr/bin/env python3
"""stage_images.py - renders the stage pages' pictures again and compares them with docs/images.

    python3 tools/stage_images.py --build build                 # render into build/stage-images, compare
    python3 tools/stage_images.py --build build --out /tmp/si   # render into /tmp/si
    python3 tools/stage_images.py --build build --update        # and replace the committed images that differ
    python3 tools/stage_images.py --list                        # the table: image, command, needs ../shared

IMAGES below is the one record of how each picture of docs/stages/*.md (and the README's
showcase.png, and docs/renderer.md's samplers-and-filters picture) is made: the stage
program and its arguments, run in the output folder, the scene paths relative to the
repository and the meshes to its sibling ../shared (an image that needs them is skipped
when ../shared/meshes is absent). Two pictures show a mistake planted on purpose (a mirror
or glass ray started at the hit point): they are rendered by a copy of the repository with
that one line changed, configured and built in <out>/planted (about 25 s each on the
2-core machine); --no-planted leaves them out, --only picks images by name.

Each rendered image is decoded (PNG with zlib and the PNG filters, standard library only)
and compared pixel by pixel with the committed one: one line per image, the number of
differing pixels and the largest channel difference. --update then replaces, atomically
and only after every render succeeded, the committed images whose pixels differ (an image
whose pixels are equal is left alone, whatever its bytes). --check is the ctest check
docs.images: only the images marked cheap (each renders in a second or so), one line per
stale image. The exit code is 0 when every image rendered equals its committed one (or
--update replaced it), 1 when one differs or a render failed, 2 for a wrong command line or
a PNG that cannot be read. Python 3 standard library only.
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

REPO = Path(__file__).resolve().parent.parent
IMAGES_DIR = Path("docs/images")


@dataclass(frozen=True)
class Plant:
    """A mistake planted on purpose: `old` replaced by `new` (once) in `path`."""
    path: str
    old: str
    new: str
    what: str


@dataclass(frozen=True)
class Render:
    """One run of a stage program, in the output folder, and the images it writes there."""
    program: str
    args: Tuple[str, ...]
    images: Tuple[str, ...]
    cheap: bool = True           # renders in about a second: the ctest check docs.images runs it
    plant: Optional[Plant] = None
    zoom: Optional[Tuple[int, int, int, int, int]] = None  # then each image's (x, y, w, h) crop, magnified k times

    @property
    def shared(self) -> bool:
        # an OBJ of ../shared named on the command line, or by the scene file (cornell.scene)
        return any(a.startswith("../shared/") or (a.endswith(".scene") and (REPO / a).is_file() and
                                                  "shared/meshes/" in (REPO / a).read_text(encoding="utf-8"))
                   for a in self.args)

    def command(self) -> str:
        text = " ".join([self.program] + [shlex.quote(a) for a in self.args])
        if self.zoom:
            x, y, w, h, k = self.zoom
            text += f", then the {w}x{h} pixels from ({x}, {y}) magnified {k} times"
        return text


NO_OFFSET_07 = Plant("include/rt/shading/raytracer.hpp",
                     "const ray reflected = spawn_ray(hit, reflect(r.direction, hit.normal));",
                     "const ray reflected = ray{hit.point, reflect(r.direction, hit.normal)};",
                     "the mirror ray started at the hit point (ray{hit.point, r})")
NO_OFFSET_09 = Plant("include/rt/shading/dielectric.hpp",
                     "return ray_color_glass(s, accel, spawn_ray(hit, direction), depth + 1, options);",
                     "return ray_color_glass(s, accel, ray{hit.point, direction}, depth + 1, options);",
                     "new rays started at the hit point (ray{hit.point, t})")

# The pictures of the pages, with the commands the pages show (docs/stages/NN-*.md, "Expected
# images" or "What you should see"). A render's images are the files it writes under these
# names; the program's other outputs are ignored.
IMAGES: Tuple[Render, ...] = (
    Render("stage02_generate_rays", ("scenes/showcase.scene", "-o", "02-rays-perspective.png"),
           ("02-rays-perspective.png",)),
    # the page shows the middle 48 x 32 pixels of the 640 x 360 showcase, magnified 8 times
    Render("stage02_generate_rays", ("scenes/showcase.scene", "-o", "rays.png", "--edge", "02-edge"),
           ("02-edge-1.png", "02-edge-16.png"), zoom=(296, 164, 48, 32, 8)),
    Render("stage02_generate_rays", ("scenes/showcase.scene", "-o", "02-rays-orthographic.png",
                                     "--projection", "orthographic"),
           ("02-rays-orthographic.png",)),
    Render("stage03_sphere", ("scenes/spheres.scene", "-o", "03-spheres"),
           ("03-spheres-hit.png", "03-spheres-normal.png", "03-spheres-depth.png")),
    Render("stage03_sphere", ("scenes/far-spheres.scene", "-o", "03-far-spheres-textbook", "--method", "textbook"),
           ("03-far-spheres-textbook-normal.png",)),
    Render("stage03_sphere", ("scenes/far-spheres.scene", "-o", "03-far-spheres-stable", "--method", "stable"),
           ("03-far-spheres-stable-normal.png",)),
    # not in ctest: 3-5 s each, nearly all of it spent timing the student's list (one row in 214)
    Render("stage04_triangle", ("../shared/meshes/stanford-bunny.obj", "-o", "04-bunny-normals.png"),
           ("04-bunny-normals.png",), cheap=False),
    Render("stage04_triangle", ("../shared/meshes/stanford-bunny.obj", "--mode", "depth", "-o", "04-bunny-depth.png"),
           ("04-bunny-depth.png",), cheap=False),
    Render("stage04_triangle", ("../shared/meshes/CornellBox-Original.obj", "--size", "480x480",
                                "-o", "04-cornell-normals.png"),
           ("04-cornell-normals.png",)),
    Render("stage04_triangle", ("scenes/showcase.scene", "-o", "04-showcase-normals.png"),
           ("04-showcase-normals.png",)),
    Render("stage05_shading", ("scenes/shading.scene", "-o", "05-shading.png"), ("05-shading.png",)),
    Render("stage06_shadows", ("scenes/shadows.scene", "-o", "06-shadows-robust.png"), ("06-shadows-robust.png",)),
    Render("stage06_shadows", ("scenes/shadows.scene", "-o", "06-shadows-fixed-epsilon.png",
                               "--offset", "fixed", "--epsilon", "1e-4"),
           ("06-shadows-fixed-epsilon.png",)),
    Render("stage07_reflections", ("scenes/showcase.scene", "-o", "07-showcase.png"), ("07-showcase.png",)),
    Render("stage07_reflections", ("scenes/mirrors.scene", "-o", "07-mirrors.png"), ("07-mirrors.png",)),
    Render("stage07_reflections", ("scenes/showcase.scene", "-o", "07-showcase-no-offset.png"),
           ("07-showcase-no-offset.png",), cheap=False, plant=NO_OFFSET_07),
    Render("stage08_output", ("scenes/showcase.scene", "-o", "showcase.png", "--quiet"), ("showcase.png",)),
    Render("stage08_gallery", ("08-samplers-filters.png",), ("08-samplers-filters.png",)),
    Render("stage09_refraction", ("scenes/glass.scene", "-o", "09-glass.png"), ("09-glass.png",)),
    Render("stage09_refraction", ("scenes/glass.scene", "-o", "09-glass-depth-2.png", "--max-depth", "2"),
           ("09-glass-depth-2.png",)),
    Render("stage09_refraction", ("scenes/glass.scene", "-o", "09-glass-no-offset.png"),
           ("09-glass-no-offset.png",), cheap=False, plant=NO_OFFSET_09),
    # not in ctest: 64 samples a pixel take 6 s; the 4-sample picture below runs the same code in 0.4 s
    Render("stage10_distribution", ("scenes/soft.scene", "-o", "10-soft.png"), ("10-soft.png",), cheap=False),
    Render("stage10_distribution", ("scenes/soft.scene", "-o", "10-soft-4.png", "--spp", "4"), ("10-soft-4.png",)),
    # not in ctest: 64 samples a pixel take 7 s; the 4-sample pictures below run the same code in 0.5 s each
    Render("stage11_path_tracing", ("scenes/cornell.scene", "-o", "11-cornell.png"), ("11-cornell.png",), cheap=False),
    Render("stage11_path_tracing", ("scenes/cornell.scene", "-o", "11-cornell-cosine-4.png", "--spp", "4",
                                    "--strategy", "cosine"), ("11-cornell-cosine-4.png",)),
    Render("stage11_path_tracing", ("scenes/cornell.scene", "-o", "11-cornell-nee-4.png", "--spp", "4",
                                    "--strategy", "nee"), ("11-cornell-nee-4.png",)),
    Render("stage11_path_tracing", ("scenes/cornell.scene", "-o", "11-cornell-mis-4.png", "--spp", "4"),
           ("11-cornell-mis-4.png",)),
)


# The pages whose pictures the table must hold (the viewer's screenshots are not renders).
PAGES = ("README.md", "docs/renderer.md", "docs/stages/*.md")
SCREENSHOTS = "viewer-"


def pictures_of_pages(repo: Path) -> List[Tuple[str, int, int, str]]:
    """Every docs/images picture the pages show: (page, line, column, image name)."""
    found = []
    pattern = re.compile(r"\]\((?:\.\./)?(?:docs/)?images/([^)\s]+\.png)\)")
    for glob in PAGES:
        for page in sorted(repo.glob(glob)):
            for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
                for m in pattern.finditer(line):
                    if not m.group(1).startswith(SCREENSHOTS):
                        found.append((str(page.relative_to(repo)), number, m.start(1) + 1, m.group(1)))
    return found


def unmade_pictures(repo: Path) -> List[str]:
    """One line per picture a page shows that no render of IMAGES makes."""
    made = {i for r in IMAGES for i in r.images}
    return [f"{page}:{line}:{column}: expected a picture tools/stage_images.py makes, found {image}; hint: add "
            f"the command that makes it to IMAGES in tools/stage_images.py"
            for page, line, column, image in pictures_of_pages(repo) if image not in made]


class BadInput(Exception):
    """A problem with the input: one line, file:line:col: expected X, found Y; hint."""


# ---------------------------------------------------------------- PNG (RFC 2083 / PNG spec 2nd ed.)

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}  # color type -> samples per pixel (palettes are not written by rt)


@dataclass
class Picture:
    width: int
    height: int
    channels: int
    data: bytes  # rows top to bottom, `channels` bytes a pixel


def unfilter(raw: bytes, width: int, height: int, bpp: int, name: str) -> bytes:
    """Undoes the five filters of the PNG spec (sec. 9) on 8-bit, non-interlaced rows."""
    stride = width * bpp
    if len(raw) < height * (stride + 1):
        raise BadInput(f"{name}:1:1: expected {height * (stride + 1)} bytes of image data, "
                       f"found {len(raw)}; hint: the file is cut short")
    out = bytearray(height * stride)
    previous = bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind = raw[start]
        row = bytearray(raw[start + 1:start + 1 + stride])
        if kind == 0:
            pass
        elif kind == 1:
            for x in range(bpp, stride):
                row[x] = (row[x] + row[x - bpp]) & 0xFF
        elif kind == 2:
            row = bytearray((r + p) & 0xFF for r, p in zip(row, previous))
        elif kind == 3:
            for x in range(stride):
                left = row[x - bpp] if x >= bpp else 0
                row[x] = (row[x] + ((left + previous[x]) >> 1)) & 0xFF
        elif kind == 4:  # Paeth (sec. 9.4), inlined: this loop is most of the time a decode takes
            for x in range(stride):
                b = previous[x]
                if x >= bpp:
                    a = row[x - bpp]
                    c = previous[x - bpp]
                else:
                    a = c = 0
                pa = b - c if b > c else c - b          # |p - a|, p = a + b - c
                pb = a - c if a > c else c - a          # |p - b|
                pc = a + b - c - c
                pc = pc if pc > 0 else -pc              # |p - c|
                row[x] = (row[x] + (a if pa <= pb and pa <= pc else (b if pb <= pc else c))) & 0xFF
        else:
            raise BadInput(f"{name}:1:1: expected a row filter 0-4, found {kind} in row {y}; "
                           f"hint: the file is damaged")
        out[y * stride:(y + 1) * stride] = row
        previous = row
    return bytes(out)


def read_png(path: Path, name: Optional[str] = None) -> Picture:
    name = name or str(path)
    data = path.read_bytes()
    if not data.startswith(PNG_SIGNATURE):
        raise BadInput(f"{name}:1:1: expected the PNG signature, found {data[:8]!r}; hint: is it a PNG file?")
    pos = len(PNG_SIGNATURE)
    header = None
    idat = bytearray()
    while pos + 8 <= len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length:
            raise BadInput(f"{name}:1:1: expected {length} bytes of chunk {kind!r}, found {len(body)}; "
                           f"hint: the file is cut short")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    if header is None:
        raise BadInput(f"{name}:1:1: expected an IHDR chunk, found none; hint: the file is damaged")
    width, height, depth, color, _, _, interlace = header
    if depth != 8 or color not in CHANNELS or interlace != 0:
        raise BadInput(f"{name}:1:1: expected an 8-bit, non-interlaced grey or RGB(A) PNG, found bit depth "
                       f"{depth}, color type {color}, interlace {interlace}; hint: the stage programs write "
                       f"8-bit RGB")
    try:
        raw = zlib.decompress(bytes(idat))
    except zlib.error as e:
        raise BadInput(f"{name}:1:1: expected zlib-compressed image data, found data zlib rejects ({e}); "
                       f"hint: the file is damaged") from None
    channels = CHANNELS[color]
    return Picture(width, height, channels, unfilter(raw, width, height, channels, name))


@dataclass
class Difference:
    pixels: int        # pixels with any channel different
    largest: int       # the largest difference of one channel, 0..255
    total: int         # pixels in the image
    note: str = ""     # a different size or channel count

    @property
    def equal(self) -> bool:
        return self.pixels == 0 and not self.note

    def __str__(self) -> str:
        if self.note:
            return self.note
        if self.equal:
            return f"equal ({self.total} pixels)"
        share = 100.0 * self.pixels / self.total
        return (f"{self.pixels} of {self.total} pixels differ ({share:.2f}%), "
                f"largest channel difference {self.largest}")


def write_png(path: Path, picture: Picture) -> None:
    """An 8-bit PNG of `picture`, every row unfiltered (filter 0), written atomically."""
    color = {1: 0, 2: 4, 3: 2, 4: 6}[picture.channels]
    stride = picture.width * picture.channels
    raw = b"".join(b"\0" + picture.data[y * stride:(y + 1) * stride] for y in range(picture.height))

    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", picture.width, picture.height, 8, color, 0, 0, 0)
    write_atomically(PNG_SIGNATURE + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
                     + chunk(b"IEND", b""), path)


def magnify(picture: Picture, x: int, y: int, w: int, h: int, k: int) -> Picture:
    """The w x h pixels from (x, y), each made a k x k block."""
    n = picture.channels
    if x + w > picture.width or y + h > picture.height:
        raise RuntimeError(f"cannot crop {w}x{h} pixels from ({x}, {y}) of a {picture.width}x{picture.height} image")
    rows = []
    for row in range(y, y + h):
        start = (row * picture.width + x) * n
        line = b"".join(picture.data[start + i * n:start + (i + 1) * n] * k for i in range(w))
        rows.append(line * k)
    return Picture(w * k, h * k, n, b"".join(rows))


def compare(rendered: Picture, committed: Picture) -> Difference:
    total = committed.width * committed.height
    if (rendered.width, rendered.height) != (committed.width, committed.height):
        return Difference(total, 255, total, f"size {rendered.width}x{rendered.height}, "
                                            f"committed {committed.width}x{committed.height}")
    if rendered.channels != committed.channels:
        return Difference(total, 255, total, f"{rendered.channels} channels, committed {committed.channels}")
    n = committed.channels
    a, b = rendered.data, committed.data
    if a == b:
        return Difference(0, 0, total)
    pixels = 0
    largest = 0
    for p in range(0, len(a), n):
        pa, pb = a[p:p + n], b[p:p + n]
        if pa != pb:
            pixels += 1
            largest = max(largest, max(abs(x - y) for x, y in zip(pa, pb)))
    return Difference(pixels, largest, total)


# ---------------------------------------------------------------- rendering

def shared_dir(repo: Path) -> Path:
    return repo.parent / "shared"


def resolve(arg: str, repo: Path) -> str:
    """A path of the table (as the pages write it) made absolute; other arguments unchanged."""
    if arg.startswith("../shared/"):
        return str(shared_dir(repo) / arg[len("../shared/"):])
    if arg.startswith("scenes/"):
        return str(repo / arg)
    return arg


def run_render(render: Render, program: Path, folder: Path, repo: Path) -> Optional[str]:
    """Runs one render in `folder`; None, or what went wrong in one line."""
    folder.mkdir(parents=True, exist_ok=True)
    for image in render.images:
        (folder / image).unlink(missing_ok=True)
    if not program.is_file():
        return f"no program {program}; hint: build it (cmake --build BUILD --target {render.program})"
    p = subprocess.run([str(program)] + [resolve(a, repo) for a in render.args], cwd=folder,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if p.returncode != 0:
        said = (p.stderr or p.stdout).decode("utf-8", "replace").strip().splitlines()
        return f"exit code {p.returncode}: {said[-1] if said else '(nothing on stderr)'}"
    missing = [i for i in render.images if not (folder / i).is_file()]
    if missing:
        return f"exit code 0 but no {', '.join(missing)} written"
    if render.zoom:
        for image in render.images:
            write_png(folder / image, magnify(read_png(folder / image), *render.zoom))
    return None


def planted_programs(renders: Sequence[Render], repo: Path, work: Path, jobs: int) -> Dict[Render, Path]:
    """Builds each planted render's program in a copy of the repository with its mistake planted.

    Each copy has one mistake, so that a program shows exactly the mistake its page describes.
    The copies hold the files git knows (tracked and untracked-but-not-ignored)."""
    if not renders:
        return {}
    git = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                         cwd=repo, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    if git.returncode == 0:
        listed = git.stdout.decode().split("\0")
    else:  # not a git checkout: every file outside build*/ folders, as make_kit.py copies
        listed = [str(f.relative_to(repo)) for f in repo.rglob("*")
                  if f.is_file() and not any(part.startswith(("build", ".git")) for part in f.relative_to(repo).parts)]
    programs: Dict[Render, Path] = {}
    for index, render in enumerate(renders):
        plant = render.plant
        assert plant is not None
        source = work / f"plant{index}" / "src"
        build = work / f"plant{index}" / "build"
        if source.exists():
            shutil.rmtree(source)
        for rel in filter(None, listed):
            if (repo / rel).is_file():
                (source / rel).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(repo / rel, source / rel)
        target = source / plant.path
        text = target.read_text()
        if text.count(plant.old) != 1:
            raise BadInput(f"{plant.path}:1:1: expected the line to plant the mistake in once, found it "
                           f"{text.count(plant.old)} times: {plant.old!r}; hint: update Plant in "
                           f"tools/stage_images.py")
        target.write_text(text.replace(plant.old, plant.new))
        configure = ["cmake", "-S", str(source), "-B", str(build), "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                     "-DRT_BUILD_TESTS=OFF", "-DRT_BUILD_BENCH=OFF", "-DRT_HEADER_CHECK=OFF", "-DRT_INSTALL=OFF"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        for step in (configure, ["cmake", "--build", str(build), "-j", str(jobs), "--target", render.program]):
            p = subprocess.run(step, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
            if p.returncode != 0:
                tail = p.stdout.decode("utf-8", "replace").strip().splitlines()[-20:]
                raise RuntimeError(f"planting {plant.what}: {' '.join(step)} failed:\n" + "\n".join(tail))
        programs[render] = build / "stages" / render.program
    return programs


def write_atomically(data: bytes, target: Path) -> None:
    fd, temporary = tempfile.mkstemp(prefix="." + target.name + ".", dir=target.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(temporary, 0o644)
        os.replace(temporary, target)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def print_table() -> None:
    print("| image | command (run in the output folder) | ../shared | ctest docs.images |")
    print("|---|---|---|---|")
    for r in IMAGES:
        command = r.command() + (f"  (built with {r.plant.what} in {r.plant.path})" if r.plant else "")
        print(f"| {', '.join(r.images)} | `{command}` | {'yes' if r.shared else 'no'} | "
              f"{'yes' if r.cheap else 'no'} |")


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build", help="the build folder whose stages/ holds the programs "
                        "(default: build)")
    parser.add_argument("--programs", help="the folder holding the stage programs (default: BUILD/stages)")
    parser.add_argument("--out", help="where to render (default: BUILD/stage-images); never docs/images")
    parser.add_argument("--repo", default=str(REPO), help="the repository (default: this script's)")
    parser.add_argument("--update", action="store_true",
                        help="replace the committed images that differ, after every render succeeded")
    parser.add_argument("--check", action="store_true",
                        help="the ctest check: the cheap images only, one line per stale image")
    parser.add_argument("--no-planted", action="store_true",
                        help="leave out the images of planted mistakes (they need a build of their own)")
    parser.add_argument("--only", metavar="IMAGE[,IMAGE...]", help="only the renders making these images")
    parser.add_argument("--jobs", type=int, default=2, help="build jobs for the planted mistakes (default 2)")
    parser.add_argument("--list", action="store_true", help="print the table of images and commands")
    args = parser.parse_args(argv)

    if args.list:
        print_table()
        return 0
    if args.check and args.update:
        parser.error("--check and --update go separately")
    repo = Path(args.repo).resolve()
    build = Path(args.build).resolve()
    programs_dir = Path(args.programs).resolve() if args.programs else build / "stages"
    out = Path(args.out).resolve() if args.out else build / "stage-images"
    committed_dir = repo / IMAGES_DIR
    if out == committed_dir.resolve():
        parser.error("--out must not be docs/images: render elsewhere and pass --update")

    renders = list(IMAGES)
    if args.check:
        renders = [r for r in renders if r.cheap]
    if args.no_planted:
        renders = [r for r in renders if r.plant is None]
    if args.only:
        wanted = {w.strip() for w in args.only.split(",") if w.strip()}
        known = {i for r in IMAGES for i in r.images}
        unknown = sorted(wanted - known)
        if unknown:
            parser.error(f"--only: expected images of the table (--list), found {', '.join(unknown)}")
        renders = [r for r in renders if wanted & set(r.images)]

    unmade = unmade_pictures(repo)
    have_shared = (shared_dir(repo) / "meshes").is_dir()
    out.mkdir(parents=True, exist_ok=True)
    failed: List[str] = []
    stale: List[Tuple[str, Render, Difference]] = []
    skipped: List[str] = []
    rendered: Dict[str, Path] = {}
    started = time.monotonic()
    try:
        planted = planted_programs([r for r in renders if r.plant and (have_shared or not r.shared)],
                                   repo, out / "planted", args.jobs)
        for render in renders:
            if render.shared and not have_shared:
                skipped.append(f"{', '.join(render.images)}: skipped, no {shared_dir(repo) / 'meshes'}")
                continue
            program = planted.get(render, programs_dir / render.program)
            t0 = time.monotonic()
            problem = run_render(render, program, out, repo)
            seconds = time.monotonic() - t0
            if problem:
                failed.append(f"{', '.join(render.images)}: `{render.command()}` failed: {problem}")
                continue
            for image in render.images:
                committed = committed_dir / image
                if committed.is_file() and committed.read_bytes() == (out / image).read_bytes():
                    rendered[image] = out / image  # the same file: no need to decode it
                    if not args.check:
                        print(f"{image}: the same file ({seconds:.1f} s, `{render.command()}`)", flush=True)
                    continue
                mine = read_png(out / image)
                if not committed.is_file():
                    difference = Difference(mine.width * mine.height, 255, mine.width * mine.height,
                                            "no committed image")
                else:
                    difference = compare(mine, read_png(committed, str(IMAGES_DIR / image)))
                rendered[image] = out / image
                if not difference.equal:
                    stale.append((image, render, difference))
                if not args.check:
                    print(f"{image}: {difference} ({seconds:.1f} s, `{render.command()}`)", flush=True)
    except BadInput as e:
        print(e, file=sys.stderr)
        return 2
    except RuntimeError as e:
        print(f"stage_images: {e}", file=sys.stderr)
        return 1

    for line in skipped:
        print(line)
    for line in unmade + failed:
        print(line, file=sys.stderr)
    if args.check:
        for image, render, difference in stale:
            print(f"{IMAGES_DIR / image}: stale: `{render.command()}` renders it differently: {difference}; "
                  f"hint: if the new picture is right, "
                  f"python3 tools/stage_images.py --programs {programs_dir} --update")
        print(f"stage_images: {len(rendered)} images compared, {len(stale)} stale, {len(failed)} renders failed, "
              f"{len(skipped)} skipped ({time.monotonic() - started:.1f} s)")
        return 1 if stale or failed or unmade else 0
    if args.update:
        if failed:
            print("stage_images: nothing updated: a render failed", file=sys.stderr)
            return 1
        for image, _, _ in stale:
            write_atomically(rendered[image].read_bytes(), committed_dir / image)
            print(f"updated {IMAGES_DIR / image}")
        print(f"stage_images: {len(rendered)} images compared, {len(stale)} updated, {len(skipped)} skipped")
        return 1 if unmade else 0
    print(f"stage_images: {len(rendered)} images compared, {len(stale)} differ, {len(failed)} renders failed, "
          f"{len(skipped)} skipped ({time.monotonic() - started:.1f} s); rendered into {out}")
    return 1 if stale or failed or unmade else 0


if __name__ == "__main__":
    sys.exit(main())
