// emitters.hpp - the triangles that glow, as area lights sampled by area (stage 11).
//
// A path tracer lights a point two ways: a path that happens to meet a glowing
// surface picks up its emission Le, and next-event estimation aims a ray at a
// random point of the glowing surfaces on purpose (next_event.hpp). This
// header finds those surfaces: every triangle of the scene (a `triangle`
// statement or a mesh's face) whose material has an emission (a scene file's
// `emission`, an MTL file's Ke). A point of them is drawn uniformly over their
// total area A: a triangle with the probability of its share of the area, then
// a point uniform in it, so the density is pdf_A = 1 / A everywhere on them.
// Uniform point in a triangle (Physically Based Rendering, 3rd ed., sec.
// 13.6.5; 4th ed., sec. 6.5.4): with s = sqrt(xi1),
//     b0 = 1 - s,   b1 = xi2 s,   p = b0 a + b1 b + (1 - b0 - b1) c.
// Spheres that glow are not sampled: a path meets them, as it meets the
// background (the light of a uniform environment).
//
// A triangle glows from its front, the side from which its corners a, b, c
// turn counter-clockwise (normal (b - a) x (c - a), triangle_shape.hpp): the
// Cornell box's light faces down into the box, and nothing leaves its back
// into the thin gap under the ceiling. A sphere glows from both sides, so
// that the inside of a glowing sphere is lit.
//
//     const rt::emitter_list lights = rt::find_emitters(s);
//     const rt::emitter_sample y = rt::sample_emitters(lights, xi0, xi1, xi2); // y.point, y.pdf_area
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

#include <glm/geometric.hpp>

#include "../core/hit_record.hpp"
#include "../scene/material.hpp"
#include "../scene/mesh.hpp"
#include "../scene/scene.hpp"
#include "../core/vec.hpp"

namespace rt {

/// One glowing triangle.
struct emitter_triangle {
    vec3 a{0}, b{0}, c{0};
    color emission{0.0f};  ///< Le, leaving its front
};

/// Every glowing triangle of a scene, with the running sum of their areas.
struct emitter_list {
    std::vector<emitter_triangle> triangles;
    std::vector<double> area_before;  ///< area_before[i]: the area of triangles 0 .. i together
    double total_area = 0;            ///< A

    bool empty() const { return triangles.empty() || !(total_area > 0); }
};

/// A point drawn on the emitters: where, the unit normal of its triangle's
/// front (the side it glows from), its emission, and the density pdf_A = 1 / A
/// per unit area.
struct emitter_sample {
    vec3 point{0};
    vec3 normal{0, 1, 0};
    color emission{0.0f};
    real pdf_area = 0;
};

/// Half the length of (b - a) x (c - a).
inline double triangle_area(const vec3& a, const vec3& b, const vec3& c)
{
    const glm::dvec3 ab = glm::dvec3(b) - glm::dvec3(a), ac = glm::dvec3(c) - glm::dvec3(a);
    return 0.5 * glm::length(glm::cross(ab, ac));
}

/// The glowing triangles of `s`, in the order of its shapes and faces.
inline emitter_list find_emitters(const scene& s)
{
    emitter_list out;
    auto add = [&](const vec3& a, const vec3& b, const vec3& c, int material) {
        const rt::material& m = s.material_of(material);
        const double area = triangle_area(a, b, c);
        if (!is_emissive(m) || !(area > 0))
            return;
        out.triangles.push_back({a, b, c, m.emission});
        out.total_area += area;
        out.area_before.push_back(out.total_area);
    };
    for (const shape& item : s.shapes) {
        if (const triangle* t = std::get_if<triangle>(&item)) {
            add(t->a, t->b, t->c, t->material);
        } else if (const mesh* m = std::get_if<mesh>(&item)) {
            for (std::size_t i = 0; i < m->triangles.size(); ++i) {
                const index3& f = m->triangles[i];
                add(m->positions[f[0]], m->positions[f[1]], m->positions[f[2]], triangle_material(*m, i));
            }
        }
    }
    return out;
}

/// A point uniform over the emitters' total area, from three uniform numbers
/// in [0, 1): xi0 picks the triangle (by area), xi1 and xi2 the point in it.
/// An empty list gives pdf_area 0.
inline emitter_sample sample_emitters(const emitter_list& lights, real xi0, real xi1, real xi2)
{
    emitter_sample y;
    if (lights.empty())
        return y;
    const double target = double(xi0) * lights.total_area;
    const auto found = std::upper_bound(lights.area_before.begin(), lights.area_before.end(), target);
    const std::size_t i = std::min(std::size_t(found - lights.area_before.begin()), lights.triangles.size() - 1);
    const emitter_triangle& t = lights.triangles[i];
    const real s = std::sqrt(xi1);
    const real b0 = 1 - s, b1 = xi2 * s;
    y.point = b0 * t.a + b1 * t.b + (1 - b0 - b1) * t.c;
    y.normal = glm::normalize(glm::cross(t.b - t.a, t.c - t.a));
    y.emission = t.emission;
    y.pdf_area = real(1 / lights.total_area);
    return y;
}

/// The radiance Le the surface of `hit` sends back along the ray of direction
/// d: its material's emission, from the front of a triangle (0 from its back)
/// and from either side of a sphere.
inline color emitted_radiance(const scene& s, const hit_record& hit, const vec3& d)
{
    const material& m = s.material_of(hit.material);
    if (!is_emissive(m) || hit.shape >= s.shapes.size())
        return color(0.0f);
    const shape& item = s.shapes[hit.shape];
    vec3 front(0);
    if (const triangle* t = std::get_if<triangle>(&item)) {
        front = glm::cross(t->b - t->a, t->c - t->a);
    } else if (const mesh* mm = std::get_if<mesh>(&item)) {
        if (hit.primitive >= mm->triangles.size())
            return color(0.0f);
        const index3& f = mm->triangles[hit.primitive];
        front = glm::cross(mm->positions[f[1]] - mm->positions[f[0]], mm->positions[f[2]] - mm->positions[f[0]]);
    } else {
        return m.emission; // a sphere: both sides
    }
    return glm::dot(front, d) < 0 ? m.emission : color(0.0f);
}

/// True when the hit is on a triangle that find_emitters lists: next-event
/// estimation can aim at it, so the two strategies share its emission (mis.hpp).
inline bool hit_sampled_emitter(const scene& s, const hit_record& hit)
{
    if (hit.shape >= s.shapes.size() || !is_emissive(s.material_of(hit.material)))
        return false;
    return !std::holds_alternative<sphere>(s.shapes[hit.shape]);
}

} // namespace rt
