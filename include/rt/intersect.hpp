// intersect.hpp - the nearest hit of a ray in a whole scene (stage 04; every later stage calls it).
//
// The course's group: "loop over all objects, keep the closest hit". That loop
// is closest_hit_list, the stage-04 exercise, written for reading. The library
// (shading, shadows, reflections) uses rt::accelerator instead: built once from
// a scene, as a flat list of packed primitives or as a BVH (bvh.hpp), it
// returns exactly the same hits faster:
//
//     rt::accelerator world(scene);                   // auto: BVH unless the scene is tiny
//     rt::hit_record rec;
//     if (world.closest_hit(r, 0, rt::infinity, rec)) ...  // rec.shape, rec.primitive, rec.material
//     if (world.any_hit(shadow_ray, 0, distance)) ...     // something blocks the light
//
// Closest means: the smallest t in [tmin, tmax]; at an equal t, the later
// primitive in scene order (shapes in file order, a mesh's triangles in its
// order), which is what the list loop does when it passes the closest t so far
// as tmax. The list, the flat accelerator and the BVH all follow this rule and
// all use the robust methods (rt::hit_sphere, the watertight triangle test), so
// they agree hit for hit.
//
// Every hit record is complete: t, point and its rounding error (for
// spawn_ray), geometric and shading normals facing the ray, front_face,
// material, shape, primitive, barycentrics. A sphere's hit point and normal
// are computed again from the ray relative to the centre, in a wider type
// (refine_sphere_hit), so the normal's direction does not depend on how far
// the ray came from.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include <glm/common.hpp>

#include "bvh.hpp"
#include "error.hpp"
#include "hit_record.hpp"
#include "mesh.hpp"
#include "ray.hpp"
#include "rounding.hpp"
#include "scene.hpp"
#include "sphere_stable.hpp"
#include "triangle.hpp"
#include "vec.hpp"

namespace rt {

/// +inf as rt::real: the tmax of a ray that may go on forever.
constexpr real infinity = std::numeric_limits<real>::infinity();

/// The hit point and normal of a sphere hit that hit_sphere found on ray r,
/// computed again relative to the centre. The point p + t d itself is no
/// good for the normal when the ray comes from far away: its rounding error,
/// about u |p - c| (u the unit roundoff), can exceed R, and normalize(p - c)
/// then points anywhere (issue 19: rays from 10^8 at spheres of radius 10^-3).
/// In the wider type of sphere_stable.hpp, with f = p - c and d^ = d / |d| (Ray
/// Tracing Gems ch. 7, the stable method's perpendicular vector):
///     l = f - (f.d^) d^          the centre's perpendicular to the line,
///     s = sqrt(R^2 - |l|^2)      half the chord,
///     x = l -+ s d^              the hit relative to c (- for the nearer root),
/// so |x| = R exactly in exact arithmetic, and x's error is a few rounding
/// units of the wider type times |f|, 2^-29 times less than in float. The
/// point is c + x rounded once; its error bound is that rounding (gamma_1
/// |point|, PBR 3rd ed., sec. 3.9.4) plus 16 units of the wider type times
/// |f| + R + |c| for x's own computation. The normal is x / |x|, turned to
/// face the ray. t is left as hit_sphere computed it.
inline void refine_sphere_hit(const sphere& s, const ray& r, hit_record& rec)
{
    using wide = detail::wider_real;
    const wide f[3] = {wide(r.origin.x) - wide(s.center.x), wide(r.origin.y) - wide(s.center.y),
                       wide(r.origin.z) - wide(s.center.z)};
    const wide dw[3] = {wide(r.direction.x), wide(r.direction.y), wide(r.direction.z)};
    const wide d_length = std::sqrt(dw[0] * dw[0] + dw[1] * dw[1] + dw[2] * dw[2]);
    if (!(d_length > 0) || !std::isfinite(d_length))
        return;
    const wide d[3] = {dw[0] / d_length, dw[1] / d_length, dw[2] / d_length};
    const wide f_along = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    const wide l[3] = {f[0] - f_along * d[0], f[1] - f_along * d[1], f[2] - f_along * d[2]};
    const wide R = wide(s.radius);
    const wide chord2 = R * R - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const wide half_chord = chord2 > 0 ? std::sqrt(chord2) : wide(0);
    // which root hit_sphere took: the same call gives the same bits (the two
    // roots can be closer than t's rounding, so t alone cannot tell them apart)
    real t0 = 0, t1 = 0;
    const bool nearer = !sphere_roots_stable(s, r, t0, t1) || rec.t == t0;
    const wide along = nearer ? -half_chord : half_chord;
    const wide x[3] = {l[0] + along * d[0], l[1] + along * d[1], l[2] + along * d[2]};
    const wide x_length = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (!(x_length > 0) || !std::isfinite(x_length))
        return; // keeps hit_sphere's point and its unit normal
    const vec3 outward(real(x[0] / x_length), real(x[1] / x_length), real(x[2] / x_length));
    rec.point = vec3(real(wide(s.center.x) + x[0]), real(wide(s.center.y) + x[1]), real(wide(s.center.z) + x[2]));
    const wide largest_f = std::fmax(std::fabs(f[0]), std::fmax(std::fabs(f[1]), std::fabs(f[2])));
    const wide largest_c = std::fmax(std::fabs(wide(s.center.x)),
                                     std::fmax(std::fabs(wide(s.center.y)), std::fabs(wide(s.center.z))));
    const wide wide_error = 16 * (std::numeric_limits<wide>::epsilon() / 2) * (largest_f + R + largest_c);
    const vec3 x_real = vec3(real(x[0]), real(x[1]), real(x[2]));
    rec.point_error =
        gamma_n(5) * glm::abs(x_real) + gamma_n(1) * glm::abs(rec.point) + vec3(next_up(real(wide_error)));
    rec.front_face = dw[0] * x[0] + dw[1] * x[1] + dw[2] * x[2] <= 0;
    rec.geometric_normal = rec.front_face ? outward : -outward;
    rec.normal = rec.geometric_normal;
}

/// The closest hit of one shape in [tmin, tmax], by the library's robust
/// methods (rt::hit_sphere, the watertight test for triangles and meshes).
/// rec.shape is left to the caller.
inline bool hit_shape(const shape& item, const ray& r, real tmin, real tmax, hit_record& rec)
{
    if (const sphere* ball = std::get_if<sphere>(&item)) {
        if (!hit_sphere(*ball, r, tmin, tmax, rec))
            return false;
        refine_sphere_hit(*ball, r, rec);
        return true;
    }
    if (const triangle* tri = std::get_if<triangle>(&item))
        return hit_triangle(*tri, r, tmin, tmax, rec);
    return hit_mesh(std::get<mesh>(item), r, tmin, tmax, rec);
}

/// How the list tests one shape: its closest hit in [tmin, tmax], the record
/// filled but for rec.shape. hit_shape (the robust methods) by default; the
/// stage-04 program passes the textbook methods (stages 03 and 04) instead.
using shape_hit_function = bool (*)(const shape& item, const ray& r, real tmin, real tmax, hit_record& rec);

/// The course's group: loop over all the shapes of the scene, testing each
/// with `hit`, and keep the closest hit in [tmin, tmax]; rec.shape is the
/// index of the shape hit. At an equal t the later shape wins.
inline bool closest_hit_list(const scene& s, const ray& r, real tmin, real tmax, hit_record& rec,
                             shape_hit_function hit = hit_shape)
{
    // RT_EXERCISE_BEGIN(stage04: closest hit over the list of shapes)
    bool hit_anything = false;
    real closest = tmax;
    hit_record candidate;
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        if (hit(s.shapes[i], r, tmin, closest, candidate)) {
            hit_anything = true;
            closest = candidate.t;
            rec = candidate;
            rec.shape = std::uint32_t(i);
        }
    }
    return hit_anything;
    // RT_EXERCISE_END
}

/// Whether any shape of the scene is hit in [tmin, tmax] (the list, for shadow rays).
inline bool any_hit_list(const scene& s, const ray& r, real tmin, real tmax)
{
    hit_record unused;
    for (const shape& item : s.shapes)
        if (hit_shape(item, r, tmin, tmax, unused))
            return true;
    return false;
}

/// How an accelerator searches the scene.
enum class accelerator_kind {
    flat,      ///< every primitive, in order (packed for speed)
    bvh,       ///< the bounding volume hierarchy of bvh.hpp
    automatic  ///< "auto": flat below flat_list_crossover primitives, else bvh
};

/// Below this many primitives the flat list is faster than the BVH: the
/// crossover that bench/groups.cpp measures (docs/performance.md, experiment 4:
/// random spheres and triangles in the unit cube covering it about twice,
/// primary rays, one thread, the N where the two log-log curves of ns per ray
/// cross). With the BVH of four-triangle leaf blocks it measured 4 (3 shapes:
/// flat 101 ns, BVH 112 ns; 5 shapes: flat 122 ns, BVH 111 ns). The older
/// `stage04_triangle --crossover` experiment (docs/stages/04-triangle.md)
/// gave 6 on a different mix; either way the difference is tens of ns per ray
/// on scenes of a handful of shapes.
constexpr std::size_t flat_list_crossover = 4;

inline const char* to_string(accelerator_kind kind)
{
    switch (kind) {
    case accelerator_kind::flat: return "flat";
    case accelerator_kind::bvh: return "bvh";
    default: return "auto";
    }
}

/// "flat", "bvh" or "auto"; anything else is an rt::error.
inline accelerator_kind parse_accelerator_kind(const std::string& word)
{
    if (word == "flat")
        return accelerator_kind::flat;
    if (word == "bvh")
        return accelerator_kind::bvh;
    if (word == "auto")
        return accelerator_kind::automatic;
    throw error("expected an accelerator (flat, bvh or auto), found '" + word + "'");
}

/// Which shape, and which triangle inside a mesh, a packed primitive came from.
struct primitive_ref {
    std::uint32_t shape = 0;
    std::uint32_t primitive = 0;
};

/// The scene-level intersection: built once from a scene, then queried by
/// every ray. The scene must outlive the accelerator and must not change while
/// it is used. The queries are const and safe to call from many threads.
class accelerator {
public:
    accelerator() = default;

    explicit accelerator(const scene& s, accelerator_kind kind = accelerator_kind::automatic,
                         const bvh_options& options = {})
        : scene_(&s)
    {
        std::vector<packed_primitive> prims;
        for (std::size_t i = 0; i < s.shapes.size(); ++i) {
            const shape& item = s.shapes[i];
            if (const sphere* ball = std::get_if<sphere>(&item)) {
                prims.push_back(pack_sphere(*ball, next_id(i, 0)));
            } else if (const triangle* tri = std::get_if<triangle>(&item)) {
                prims.push_back(pack_triangle(tri->a, tri->b, tri->c, next_id(i, 0)));
            } else {
                const mesh& m = std::get<mesh>(item);
                for (std::size_t k = 0; k < m.triangles.size(); ++k) {
                    const index3& face = m.triangles[k];
                    prims.push_back(pack_triangle(m.positions[face[0]], m.positions[face[1]],
                                                  m.positions[face[2]], next_id(i, k)));
                }
            }
        }
        if (kind == accelerator_kind::automatic)
            kind = prims.size() < flat_list_crossover ? accelerator_kind::flat : accelerator_kind::bvh;
        kind_ = kind;
        if (kind_ == accelerator_kind::flat)
            flat_ = std::move(prims);
        else
            tree_ = bvh(std::move(prims), options);
    }

    /// The closest hit in [tmin, tmax] (see the top of this file), with every
    /// field of `rec` filled. Precondition: r.direction is not zero.
    bool closest_hit(const ray& r, real tmin, real tmax, hit_record& rec) const
    {
        primitive_hit h;
        const bool found = kind_ == accelerator_kind::flat ? closest_flat(flat_, r, tmin, tmax, h)
                                                           : tree_.closest(r, tmin, tmax, h);
        if (!found)
            return false;
        complete(r, tmin, tmax, h, rec);
        return true;
    }

    /// Whether anything is hit in [tmin, tmax]; cheaper than closest_hit
    /// because it stops at the first hit (shadow rays).
    bool any_hit(const ray& r, real tmin, real tmax) const
    {
        return kind_ == accelerator_kind::flat ? any_flat(flat_, r, tmin, tmax) : tree_.any(r, tmin, tmax);
    }

    /// flat or bvh (automatic is resolved when the accelerator is built).
    accelerator_kind kind() const { return kind_; }
    std::size_t primitive_count() const { return refs_.size(); }
    /// The BVH's statistics (all zero for a flat accelerator).
    const bvh_stats& stats() const { return tree_.stats(); }
    const bvh& tree() const { return tree_; }
    const primitive_ref& reference(std::uint32_t id) const { return refs_[id]; }

private:
    std::uint32_t next_id(std::size_t shape_index, std::size_t primitive)
    {
        if (refs_.size() >= std::size_t(sphere_flag - 1))
            throw error("expected at most 2^31 - 1 primitives in a scene, found more; split the scene");
        refs_.push_back(primitive_ref{std::uint32_t(shape_index), std::uint32_t(primitive)});
        return std::uint32_t(refs_.size() - 1);
    }

    void complete(const ray& r, real tmin, real tmax, const primitive_hit& h, hit_record& rec) const
    {
        const primitive_ref& ref = refs_[h.id];
        const shape& item = scene_->shapes[ref.shape];
        if (const sphere* ball = std::get_if<sphere>(&item)) {
            hit_sphere(*ball, r, tmin, tmax, rec); // the same call as in the search: the same root
            refine_sphere_hit(*ball, r, rec);
        } else {
            // the corners as packed (the same numbers as in the shape)
            const real* v = h.corners;
            const int k = h.stride;
            fill_triangle_record(vec3(v[0], v[k], v[2 * k]), vec3(v[3 * k], v[4 * k], v[5 * k]),
                                 vec3(v[6 * k], v[7 * k], v[8 * k]), r, triangle_hit{h.t, h.b0, h.b1, h.b2}, rec);
            if (const triangle* tri = std::get_if<triangle>(&item))
                rec.material = tri->material;
            else
                complete_mesh_hit(std::get<mesh>(item), ref.primitive, rec);
        }
        rec.shape = ref.shape;
        rec.primitive = ref.primitive;
    }

    const scene* scene_ = nullptr;
    accelerator_kind kind_ = accelerator_kind::flat;
    std::vector<primitive_ref> refs_;
    std::vector<packed_primitive> flat_;
    bvh tree_;
};

} // namespace rt
