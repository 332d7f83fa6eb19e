"""planted_mistakes.py - every mistake a stage page lists, as a change to the reference.

Each stage page (docs/stages/NN-*.md) has a section "Common mistakes": a table
whose rows start with the mistake, or a list whose items start with it in bold.
MISTAKES holds one Mistake per row or item: the edit that makes it in a kit whose
exercises are solved, the stage suite that shows it, the test case that must fail
first there and words its failure output must hold (the hint naming the mistake).
check_kit.py --mistakes plants them one at a time (tools/check_kit.py); the
tools' tests check that every row of every page has exactly one (page_items,
coverage). A row whose mistake cannot be written as a change to the code does
not belong in a page's table: say it in the text instead.

Python 3 standard library only.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple


@dataclass(frozen=True)
class Edit:
    path: str   # relative to the kit (and the reference)
    old: str    # text found exactly once in the file
    new: str


@dataclass(frozen=True)
class Mistake:
    stage: int          # the page that lists it
    row: str            # words of the row (table: first cell; list: the bold words) naming it
    edits: Tuple[Edit, ...]
    first: str          # the start of the name of the test case that must fail first
    names: Tuple[str, ...]  # words the first failing case's output must hold
    suite: int = 0      # the stage whose suite shows it (0: the page's own)

    @property
    def shown_by(self) -> int:
        return self.suite or self.stage

    def label(self) -> str:
        return f"stage {self.stage:02d}: {self.row}"


def _m(stage: int, row: str, edits: Sequence[Tuple[str, str, str]], first: str, names: Sequence[str],
       suite: int = 0) -> Mistake:
    return Mistake(stage, row, tuple(Edit(*e) for e in edits), first, tuple(names), suite)


CAMERA = "include/rt/camera/camera.hpp"
CAMERA_STATEMENT = "include/rt/input/camera_statement.hpp"
SAMPLING = "include/rt/camera/pixel_sampling.hpp"
SPHERE = "include/rt/intersection/sphere.hpp"
TRIANGLE = "include/rt/intersection/triangle.hpp"
HIT_LIST = "include/rt/intersection/hit_list.hpp"
SLAB = "include/rt/intersection/slab.hpp"
GROUPS = "include/rt/intersection/groups.hpp"
SHADING = "include/rt/shading/shading.hpp"
RAYTRACER = "include/rt/shading/raytracer.hpp"
TONEMAP = "include/rt/output/tonemap.hpp"
TRANSFER = "include/rt/output/transfer.hpp"
DIELECTRIC = "include/rt/shading/dielectric.hpp"
REFRACTION = "include/rt/shading/refraction.hpp"
AREA_LIGHT = "include/rt/scene/area_light.hpp"
THIN_LENS = "include/rt/camera/thin_lens.hpp"
GLOSSY = "include/rt/shading/glossy.hpp"
HEMISPHERE = "include/rt/path_tracing/hemisphere.hpp"
LAMBERTIAN = "include/rt/path_tracing/lambertian.hpp"
NEXT_EVENT = "include/rt/path_tracing/next_event.hpp"
MIS = "include/rt/path_tracing/mis.hpp"
ROULETTE = "include/rt/path_tracing/roulette.hpp"
ADAPTIVE = "include/rt/path_tracing/adaptive.hpp"

_JITTER_DRAWS = ("            const real xi1 = real(rng.next_float()); // one draw per statement: a fixed order\n"
                 "            const real xi2 = real(rng.next_float());\n")
_QUANTIZE = ("include/rt/core/byte_level.hpp", "    return nearest_byte_level(v);",
             "    return std::uint8_t(v * 255.0f);")

MISTAKES: List[Mistake] = [
    # --- stage 01 ---
    _m(1, "`scene_bounds` skips meshes",
       [("include/rt/scene/scene.hpp",
         "        box.grow(std::visit([](const auto& concrete) { return bounds(concrete); }, item));",
         "        if (!std::holds_alternative<mesh>(item))\n"
         "            box.grow(std::visit([](const auto& concrete) { return bounds(concrete); }, item));")],
       "a mesh path is relative to the scene file", ["the mesh was skipped"]),
    _m(1, "fov checked as a closed interval",
       [(CAMERA_STATEMENT, "if (!(fov > 0 && fov < 180))", "if (!(fov >= 0 && fov <= 180))")],
       "bad scenes", ["a field of view between 0 and 180 degrees) for field of view 0, but the scene loaded"]),
    _m(1, "the position taken after reading the value",
       [(CAMERA_STATEMENT, 'throw make_error(where, "a field of view between 0 and 180 degrees"',
         'throw make_error(line.here(), "a field of view between 0 and 180 degrees"')],
       "bad scenes", ["column"]),
    # --- stage 02 ---
    _m(2, "rows counted from the top",
       [(CAMERA, "const real v = win.b + (win.t - win.b) * y / real(gen.ny);",
         "const real v = win.t - (win.t - win.b) * y / real(gen.ny);")],
       "generate_ray takes the film position as it is", ["rows counted from the top"]),
    _m(2, "a half-pixel shift",
       [(CAMERA, "const real u = win.l + (win.r - win.l) * x / real(gen.nx);",
         "const real u = win.l + (win.r - win.l) * (x + real(0.5)) / real(gen.nx);"),
        (CAMERA, "const real v = win.b + (win.t - win.b) * y / real(gen.ny);",
         "const real v = win.b + (win.t - win.b) * (y + real(0.5)) / real(gen.ny);")],
       "generate_ray takes the film position as it is", ["a half-pixel shift"]),
    _m(2, "`u = w x up`",
       [(CAMERA, "f.u = glm::normalize(glm::cross(up, f.w));", "f.u = glm::normalize(glm::cross(f.w, up));")],
       "the frame is orthonormal and right-handed", ["v must lean towards up"]),
    _m(2, "the field of view not halved",
       [(CAMERA, "fov_degrees * pi / real(360)", "fov_degrees * pi / real(180)")],
       "field of view to window keeps the aspect ratio", ["the field of view not halved"]),
    _m(2, "the direction not normalised in `direction_to_color`",
       [("include/rt/camera/ray_image.hpp", "const vec3 unit = glm::normalize(d);", "const vec3 unit = d;")],
       "direction to color maps", ["normalise the direction first"]),
    _m(2, "samples in [0, 1) instead of pixel (i, j)",
       [(SAMPLING, "positions.emplace_back(real(i) + (real(a) + xi1) / real(n), real(j) + (real(b) + xi2) / real(n));",
         "positions.emplace_back((real(a) + xi1) / real(n), (real(b) + xi2) / real(n));\n"
         "            (void)i, (void)j;")],
       "jittered samples: n x n of them", ["a sample must lie in the pixel's square"]),
    _m(2, "one random point anywhere in the pixel",
       [(SAMPLING, "positions.emplace_back(real(i) + (real(a) + xi1) / real(n), real(j) + (real(b) + xi2) / real(n));",
         "positions.emplace_back(real(i) + xi1, real(j) + xi2);")],
       "jittered samples: n x n of them", ["each of the n x n cells of the pixel holds exactly one sample"]),
    _m(2, "no jitter",
       [(SAMPLING, _JITTER_DRAWS, "            const real xi1 = real(0.5), xi2 = real(0.5);\n"
                                  "            (void)rng;\n")],
       "jittered samples: the same generator state", ["every sample is jittered"]),
    _m(2, "one random number for both x and y",
       [(SAMPLING, "const real xi2 = real(rng.next_float());", "const real xi2 = xi1;")],
       "jittered samples: x and y are jittered independently", ["draw xi1 and xi2 separately"]),
    _m(2, "one pair (xi1, xi2) drawn once and used in every cell",
       [(SAMPLING, "    for (int b = 0; b < n; ++b)\n        for (int a = 0; a < n; ++a) {\n" + _JITTER_DRAWS,
         "    const real xi1 = real(rng.next_float());\n    const real xi2 = real(rng.next_float());\n"
         "    for (int b = 0; b < n; ++b)\n        for (int a = 0; a < n; ++a) {\n")],
       "jittered samples: every cell draws its own offsets", ["one xi1 reused in every cell"]),
    _m(2, "a generator of your own",
       [(SAMPLING, _JITTER_DRAWS,
         "            const real xi1 = real(std::rand()) / real(RAND_MAX);\n"
         "            const real xi2 = real(std::rand()) / real(RAND_MAX);\n"
         "            (void)rng;\n")],
       "jittered samples: the same generator state", ["draw every random number from the generator passed in"]),
    _m(2, "truncating in `quantize`", [_QUANTIZE], "PPM output", ["each round(255"]),
    _m(2, "the sum divided by all the samples, not those inside",
       [(SAMPLING, "return inside > 0 ? sum / float(inside) : color(0);",
         "return inside > 0 ? sum / float(positions.size()) : color(0);")],
       "box reconstruction: samples outside the pixel count for nothing", ["divided by all 8 samples"]),
    # --- stage 03 ---
    _m(3, "the far root returned first",
       [(SPHERE, "        t = (-dpc + root) / dd;", "        t = (-dpc - root) / dd;"),
        (SPHERE, "real t = (-dpc - root) / dd;", "real t = (-dpc + root) / dd;")],
       "closed-form hits", ["the nearer root"]),
    _m(3, "`d` normalised, or `t` divided by",
       [(SPHERE, "const vec3& d = r.direction;", "const vec3 d = glm::normalize(r.direction);")],
       "closed-form hits", ["do not normalise d"]),
    _m(3, "`tmin < t` instead of `tmin <= t`",
       [(SPHERE, "    if (!(tmin <= t && t <= tmax)) {", "    if (!(tmin < t && t <= tmax)) {"),
        (SPHERE, "        if (!(tmin <= t && t <= tmax))", "        if (!(tmin < t && t <= tmax))")],
       "tmin and tmax are respected", ["tmin <= t"]),
    _m(3, "the record written on a miss",
       [(SPHERE, "    real t = (-dpc - root) / dd;\n", "    real t = (-dpc - root) / dd;\n"
                                                         "    fill_sphere_record(s, r, t, rec);\n")],
       "the material index is copied", ["untouched"]),
    _m(3, "`if (t < tmin || t > tmax)`",
       [(SPHERE, "    if (!(tmin <= t && t <= tmax)) {", "    if (t < tmin || t > tmax) {"),
        (SPHERE, "        if (!(tmin <= t && t <= tmax))", "        if (t < tmin || t > tmax)")],
       "a degenerate ray (d = 0) misses", ["NaN"]),
    # --- stage 04 ---
    _m(4, "one-sided", [(TRIANGLE, "if (det == 0) //", "if (det <= 0) //")],
       "Moller-Trumbore and the watertight test", ["the test is two-sided"]),
    _m(4, "`u > 0` or `u + v < 1`", [(TRIANGLE, "if (u < 0 || u > 1)", "if (u <= 0 || u > 1)")],
       "Moller-Trumbore and the watertight test", ["the edges are closed"]),
    _m(4, "b1 and b2 swapped",
       [(TRIANGLE, "triangle_hit{t, 1 - u - v, u, v}", "triangle_hit{t, 1 - u - v, v, u}")],
       "Moller-Trumbore and the watertight test", ["the weight of corner b"]),
    _m(4, "`tmax` not narrowed in the list",
       [(HIT_LIST, "if (hit(s.shapes[i], r, tmin, closest, candidate)) {",
         "if (hit(s.shapes[i], r, tmin, tmax, candidate)) {"),
        (HIT_LIST, "    return hit_anything;", "    (void)closest;\n    return hit_anything;")],
       "the closest hit over the groups is the closest hit of the list",
       ["your groups found a nearer hit than your list"]),
    _m(4, "the earlier shape kept at a tie",
       [(HIT_LIST, "if (hit(s.shapes[i], r, tmin, closest, candidate)) {",
         "if (hit(s.shapes[i], r, tmin, closest, candidate) && (!hit_anything || candidate.t < closest)) {")],
       "the closest hit over the groups is the closest hit of the list", ["your list kept the earlier shape"]),
    _m(4, "slab: the near plane chosen by the sign of d_k",
       [(SLAB, "        if (a >= 0) {", "        if (r.direction[k] >= 0) {")],
       "the slab test, hits and misses worked out by hand", ["1 / -0 = -inf"]),
    _m(4, "slab: tnear not raised to tmin",
       [(SLAB, "std::max(std::max(std::max(t_near[0], t_near[1]), t_near[2]), tmin);",
         "std::max(std::max(t_near[0], t_near[1]), t_near[2]);\n    (void)tmin;")],
       "the slab test, hits and misses worked out by hand", ["tmin"]),
    _m(4, "build: a node's box not grown by all its items",
       [(GROUPS, "        for (std::uint32_t k = first; k < first + count; ++k) {\n            box.grow(",
         "        for (std::uint32_t k = first; k + 1 < first + count; ++k) {\n            box.grow(")],
       "the groups hold every item in exactly one leaf", ["to enclose its items' boxes"]),
    _m(4, "traversal: the left child always first",
       [(GROUPS, "if (t_left <= t_right) {", "if (t_left == t_left) {")],
       "a ray that misses the root box tests no item", ["visit the nearer child first"]),
    _m(4, "traversal: the tie rule forgotten",
       [(GROUPS, "if (!found || candidate.t < closest || item > best_item) {",
         "if (!found || candidate.t < closest || (false && item > best_item)) {")],
       "the closest hit over groups built by hand: a box entered a rounding error", ["The tie rule"]),
    _m(4, "traversal: a box skipped under rounding",
       [(GROUPS, "if (t_enter > closest * slab_robust_far_factor)", "if (t_enter > closest)")],
       "the closest hit over groups built by hand: a box entered a rounding error", ["skipped under rounding"]),
    # --- stage 05 ---
    _m(5, "The half vector not normalised",
       [(SHADING, "const vec3 h = glm::normalize(v + l);", "const vec3 h = v + l;")],
       "blinn_phong where h = n", ["normalise the half vector"]),
    _m(5, "Phong's `R.v` in place of `n.h`",
       [(SHADING, "const vec3 h = glm::normalize(v + l);", "const vec3 R = real(2) * glm::dot(n, l) * n - l;"),
        (SHADING, "glm::dot(n, h)", "glm::dot(R, v)")],
       "blinn_phong: the highlight is (n.h)^p", ["Phong's R.v"]),
    _m(5, "No `max(0, ...)` on the diffuse cosine",
       [(SHADING, "float(std::max(real(0), glm::dot(n, l)))", "float(glm::dot(n, l))")],
       "blinn_phong: the highlight peaks at ks I", ["max(0, n.l)"]),
    _m(5, "No `max(0, ...)` on the specular cosine",
       [(SHADING, "std::max(real(0), glm::dot(n, h))", "glm::dot(n, h)")],
       "blinn_phong: the highlight peaks at ks I", ["clamp n.h at 0"]),
    _m(5, "l the wrong way round",
       [(SHADING, "glm::normalize(v + l)", "glm::normalize(v - l)"),
        (SHADING, "glm::dot(n, l)", "glm::dot(n, -l)")],
       "blinn_phong where h = n", ["l is the unit direction from the point towards the light"]),
    _m(5, "An ambient term inside `blinn_phong`",
       [(SHADING, "return m.kd * I * diffuse", "return m.ka * I + m.kd * I * diffuse")],
       "blinn_phong where h = n", ["blinn_phong has no ambient term"]),
    # --- stage 07 ---
    _m(7, "No offset on the reflected ray",
       [(RAYTRACER, "const ray reflected = spawn_ray(hit, reflect(r.direction, hit.normal));",
         "const ray reflected{hit.point, reflect(r.direction, hit.normal)};")],
       "a mirror ball reflects the background", ["start it off the surface"]),
    _m(7, "`+` instead of `-` in `reflect`",
       [(RAYTRACER, "return d - real(2) * glm::dot(d, n) * n;", "return d + real(2) * glm::dot(d, n) * n;")],
       "reflect: same length", ["d - 2 (d.n) n"]),
    _m(7, "No depth cap",
       [(RAYTRACER, "if (mirror && depth < s.max_depth) {", "if (mirror) {")],
       "a mirror shows km times the color", ["depth < s.max_depth"]),
    _m(7, "`depth <= max_depth`",
       [(RAYTRACER, "if (mirror && depth < s.max_depth) {", "if (mirror && depth <= s.max_depth) {")],
       "a mirror shows km times the color", ["depth < s.max_depth"]),
    # --- stage 08 ---
    _m(8, "The naive Reinhard",
       [(TONEMAP, "    if (!(x > 0.0f))\n        return 0.0f;\n    if (std::isinf(x)) // inf / inf would be NaN; the limit is 1\n"
                  "        return 1.0f;\n    return x / (1.0f + x);", "    return x / (1.0f + x);")],
       "Reinhard tone map x / (1 + x) at known points", ["return 1 for an infinite x"]),
    _m(8, "Truncating in stage 02's `quantize`", [_QUANTIZE], "PPM output", ["each round(255"], suite=2),
    _m(8, "A plain gamma 2.2 instead of the sRGB curve",
       [(TRANSFER, "    if (x <= 0.0031308f)\n        return 12.92f * x;\n"
                   "    return 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;",
         "    return x > 0.0f ? std::pow(x, 1.0f / 2.2f) : 0.0f;")],
       "sRGB encode at known points", ["plain gamma"]),
    # --- stage 09 ---
    _m(9, "New rays started at `hit.point`",
       [(DIELECTRIC, "spawn_ray(hit, direction), depth + 1", "ray{hit.point, direction}, depth + 1")],
       "a clear glass ball in a uniform sky", ["start it with rt::spawn_ray"]),
    _m(9, "Schlick with the cosine inside the glass",
       [(REFRACTION, "    if (eta > eta_t) {\n        cosine = refracted_cosine(cos_theta, eta, eta_t);\n"
                     "        if (cosine < 0)\n            return real(1);\n    }\n",
         "    if (eta > eta_t && refracted_cosine(cos_theta, eta, eta_t) < 0)\n        return real(1);\n")],
       "schlick_reflectance", ["Schlick uses the cosine on the air side"]),
    _m(9, "`d` not normalised",
       [(DIELECTRIC, "const vec3 d = glm::normalize(r.direction);", "const vec3 d = r.direction;")],
       "a clear glass ball in a uniform sky", ["refract needs d normalised first"]),
    _m(9, "No depth cap",
       [(DIELECTRIC, " && depth < s.max_depth)\n", ")\n"),
        (DIELECTRIC, "    if (depth < s.max_depth) {\n", "    {\n")],
       "a clear glass ball in a uniform sky", ["no depth cap"]),
    # --- stage 10 ---
    _m(10, "A sphere light sampled by angle instead of by cosine",
       [(AREA_LIGHT, "const real cos_theta = (1 - xi1) + xi1 * cos_max;",
         "const real cos_theta = std::cos(xi1 * std::acos(cos_max));")],
       "sample_sphere_light", ["uniform in solid angle"]),
    _m(10, "The far intersection",
       [(AREA_LIGHT, "D * cos_theta - std::sqrt(", "D * cos_theta + std::sqrt(")],
       "sample_sphere_light", ["on the part that x can see"]),
    _m(10, "The lens ray from the pinhole",
       [(THIN_LENS, "return ray{origin, in_focus - origin};",
         "(void)origin;\n    return ray{pinhole.origin, in_focus - pinhole.origin};")],
       "thin_lens_ray: each ray starts on the lens disk", ["not at the pinhole e"]),
    _m(10, "The lens ray along the pinhole direction",
       [(THIN_LENS, "return ray{origin, in_focus - origin};",
         "(void)in_focus;\n    return ray{origin, pinhole.direction};")],
       "thin_lens_ray: each ray starts on the lens disk", ["keeps the pinhole ray's direction d"]),
    _m(10, "The focus point at distance `focus` along `d`",
       [(THIN_LENS, "const vec3 in_focus = pinhole.origin + (focus / along) * pinhole.direction;",
         "const vec3 in_focus = pinhole.origin + focus * glm::normalize(pinhole.direction);\n    (void)along;")],
       "thin_lens_ray: each ray starts on the lens disk", ["at distance focus along d"]),
    _m(10, "The square of side `2a`",
       [(GLOSSY, "(xi1 - real(0.5)) * a * u + (xi2 - real(0.5)) * a * v",
         "(2 * xi1 - 1) * a * u + (2 * xi2 - 1) * a * v")],
       "glossy_direction", ["the square of side a"]),
    # --- stage 11 ---
    _m(11, "Uniform directions for cosine ones",
       [(HEMISPHERE, "    return vec3(d.x, d.y, z);", "    (void)z;\n    return uniform_hemisphere(xi1, xi2);")],
       "cosine_hemisphere: unit directions above the surface", ["the uniform hemisphere"]),
    _m(11, "The BRDF without cos / pdf",
       [(LAMBERTIAN, "s.weight = lambertian_brdf(albedo) * float(local.z / s.pdf);",
         "s.weight = lambertian_brdf(albedo);")],
       "sample_lambertian", ["albedo / pi is the BRDF alone"]),
    _m(11, "No cosine in `pdf_w`",
       [(NEXT_EVENT, "return pdf_area * distance * distance / c;", "return pdf_area * distance * distance;")],
       "solid_angle_pdf", ["without the cosine the light looks bigger"]),
    _m(11, "The balance heuristic",
       [(MIS, "const real a = pdf_a * pdf_a, b = pdf_b * pdf_b;", "const real a = pdf_a, b = pdf_b;")],
       "power_heuristic", ["balance heuristic"]),
    _m(11, "Emission counted twice with NEE",
       [(MIS, "        return 0; // next-event estimation counted it already",
         "        return 1; // next-event estimation counted it already")],
       "emission_weight and light_sample_weight", ["the light is counted twice"]),
    _m(11, "A survivor not divided by q",
       [(ROULETTE, "    throughput /= float(q);\n", "")],
       "russian_roulette", ["divided by the probability q"]),
    _m(11, "n for n - 1 in sigma",
       [(ADAPTIVE, "/ (n - 1));", "/ n);")],
       "pixel_converged", ["n instead of n - 1"]),
]


# --------------------------------------------------------------------------
# The pages' rows
# --------------------------------------------------------------------------

SECTION_RE = re.compile(r"^## Common mistakes")
BOLD_ITEM_RE = re.compile(r"^- \*\*(?P<words>.+?)\*\*")


def table_cells(line: str) -> List[str]:
    """A Markdown table row's cells; a | inside `code` belongs to its cell."""
    cells, current, in_code = [], "", False
    for c in line.strip().strip("|"):
        if c == "`":
            in_code = not in_code
        if c == "|" and not in_code:
            cells.append(current.strip())
            current = ""
        else:
            current += c
    cells.append(current.strip())
    return cells


def page_items(text: str) -> List[str]:
    """The mistakes a page's "Common mistakes" section lists: each table row's first
    cell (the header and the separator left out) and each list item's bold words."""
    items: List[str] = []
    inside, header_seen = False, False
    for line in text.splitlines():
        if line.startswith("## "):
            inside = bool(SECTION_RE.match(line))
            header_seen = False
            continue
        if not inside:
            continue
        if line.startswith("|"):
            cells = table_cells(line)
            if not header_seen:
                header_seen = True  # the header row
            elif not set(cells[0]) <= set("-: "):
                items.append(cells[0])
            continue
        header_seen = header_seen and bool(line.strip())
        m = BOLD_ITEM_RE.match(line)
        if m:
            items.append(m.group("words"))
    return items


def stage_pages(root: Path) -> Dict[int, Path]:
    """Each stage's lesson page (not its going-further page)."""
    pages = {}
    for page in sorted((root / "docs" / "stages").glob("[0-9][0-9]-*.md")):
        if "going-further" not in page.name:
            pages[int(page.name[:2])] = page
    return pages


def coverage(root: Path, mistakes: Sequence[Mistake] = MISTAKES) -> List[str]:
    """Problems, one line each: a page row no mistake plants, a row two plant, a
    mistake naming no row of its page."""
    problems = []
    pages = stage_pages(root)
    for stage, page in sorted(pages.items()):
        rel = page.relative_to(root).as_posix()
        items = page_items(page.read_text(encoding="utf-8"))
        mine = [m for m in mistakes if m.stage == stage]
        for item in items:
            planted = [m for m in mine if m.row in item]
            if not planted:
                problems.append(f"{rel}: expected a planted mistake (tools/planted_mistakes.py) for the row "
                                f"'{item[:80]}', found none; hint: add one, or take the row out of the table")
            elif len(planted) > 1:
                problems.append(f"{rel}: expected one planted mistake for the row '{item[:80]}', found "
                                f"{len(planted)}: {', '.join(m.row for m in planted)}")
        for m in mine:
            if not any(m.row in item for item in items):
                problems.append(f"{rel}: expected a row naming '{m.row}' in its Common mistakes section "
                                f"(tools/planted_mistakes.py plants it), found none")
    for m in mistakes:
        if m.stage not in pages:
            problems.append(f"tools/planted_mistakes.py: '{m.row}' is for stage {m.stage:02d}, which has no page")
    return problems


# --------------------------------------------------------------------------
# Planting
# --------------------------------------------------------------------------

def planted_texts(kit: Path, mistake: Mistake) -> Tuple[Dict[str, str], Dict[str, str], List[str]]:
    """(the original text of each file the mistake edits, the planted text, problems):
    each edit's old text must be in its file exactly once when it is applied."""
    originals: Dict[str, str] = {}
    planted: Dict[str, str] = {}
    problems = []
    for e in mistake.edits:
        if e.path not in planted:
            originals[e.path] = (kit / e.path).read_text(encoding="utf-8")
            planted[e.path] = originals[e.path]
        count = planted[e.path].count(e.old)
        if count != 1:
            problems.append(f"{e.path}: expected the text to plant '{mistake.row}' once, found it {count} "
                            f"times: {e.old[:70]!r}; hint: update tools/planted_mistakes.py")
            continue
        planted[e.path] = planted[e.path].replace(e.old, e.new)
    return originals, planted, problems


DOCTEST_RULE_RE = re.compile(r"^={20,}$", re.M)
TEST_CASE_RE = re.compile(r"^TEST CASE:\s+(?P<name>.+)$", re.M)
FAILED_RE = re.compile(r"\b(ERROR|THREW|CRASHED)\b")


@dataclass
class FirstFailure:
    case: str = ""       # the name of the first failing test case ("" when none failed)
    output: str = ""     # what doctest printed for it
    binary: str = ""


def first_failure(output: str) -> Optional[Tuple[str, str]]:
    """The first failing test case doctest reports in `output`: (name, its block)."""
    for block in DOCTEST_RULE_RE.split(output):
        m = TEST_CASE_RE.search(block)
        if m and FAILED_RE.search(block):  # (a MESSAGE alone is printed by a passing case too)
            return m.group("name").strip(), block.strip()
    return None


def judge(mistake: Mistake, found: FirstFailure) -> List[str]:
    """Problems with what planting `mistake` showed, one line each."""
    if not found.case:
        return [f"{mistake.label()}: expected '{mistake.first}...' to fail first, found every case of "
                f"stage {mistake.shown_by:02d} passing: the tests cannot see this mistake"]
    problems = []
    if not found.case.startswith(mistake.first):
        problems.append(f"{mistake.label()}: expected '{mistake.first}...' to fail first, found "
                        f"'{found.case[:90]}' failing first: {excerpt(found.output)}")
        return problems
    said = TEST_CASE_RE.sub("", found.output).lower()  # the messages, not the case's name
    missing = [w for w in mistake.names if w.lower() not in said]
    if missing:
        problems.append(f"{mistake.label()}: '{found.case[:60]}...' fails first as expected, but its message "
                        f"does not name the mistake (expected the words {', '.join(repr(w) for w in missing)}): "
                        f"{excerpt(found.output)}")
    return problems


def excerpt(block: str, limit: int = 400) -> str:
    """The first failure's lines after the case name: the check and its message."""
    lines = [l.strip() for l in block.splitlines() if l.strip()]
    start = next((k for k, l in enumerate(lines) if "ERROR" in l or "FATAL" in l), 0)
    text = " ".join(lines[start:start + 8])
    return text[:limit] + ("..." if len(text) > limit else "")


def message_excerpt(mistake: Mistake, block: str, limit: int = 160) -> str:
    """The part of the first failure's output around the first of the mistake's words."""
    flat = " ".join(TEST_CASE_RE.sub("", block).split())  # the messages, not the case's name
    at = flat.lower().find(mistake.names[0].lower()) if mistake.names else -1
    if at < 0:
        return excerpt(block, limit)
    start = max(0, at - limit // 2)
    return ("..." if start else "") + flat[start:start + limit] + "..."
