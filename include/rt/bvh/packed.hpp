// bvh/packed.hpp - one primitive as the fast path reads it, and the one rule
// for "closest".
//
// A triangle is packed as its nine corner coordinates, a sphere as its centre
// and radius: traversal reads corners where they sit, never through a mesh's
// index arrays. A hit keeps a pointer to the corners it was computed from, so
// the hit record is completed from memory already in cache. The flat list
// over packed primitives is here too: small scenes do not pay for a BVH.
//
//     const rt::packed_primitive p = rt::pack_triangle(a, b, c, 0);
//     rt::primitive_hit hit;
//     if (rt::closest_hit_flat({p}, ray, 0, rt::infinity, hit)) { /* hit.t, hit.b0 ... */ }
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "../core/aabb.hpp"
#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../intersection/sphere_stable.hpp"
#include "../core/vec.hpp"
#include "../intersection/watertight.hpp"

namespace rt {


/// Set in packed_primitive::id for a sphere.
constexpr std::uint32_t sphere_flag = 0x80000000u;

/// One primitive as traversal reads it: a triangle's corners a, b, c (v[0..8])
/// or a sphere's centre (v[0..2]) and radius (v[3]); `id` is the primitive's
/// number in scene order, with sphere_flag set for spheres.
struct packed_primitive {
    real v[9];
    std::uint32_t id;
};

inline packed_primitive pack_triangle(const vec3& a, const vec3& b, const vec3& c, std::uint32_t id)
{
    return packed_primitive{{a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}, id};
}

inline packed_primitive pack_sphere(const sphere& s, std::uint32_t id)
{
    return packed_primitive{{s.center.x, s.center.y, s.center.z, s.radius, 0, 0, 0, 0, 0}, id | sphere_flag};
}

/// A box that contains the primitive. A triangle's box is exact (the min and
/// max of its corners); a sphere's is widened by a few ulps, because c +- R
/// is rounded and the box must not cut the sphere.
inline aabb packed_bounds(const packed_primitive& p)
{
    aabb box;
    if (p.id & sphere_flag) {
        const vec3 c(p.v[0], p.v[1], p.v[2]);
        const real r = p.v[3];
        const vec3 margin = gamma_n(4) * (glm::abs(c) + vec3(r));
        box.lo = c - vec3(r) - margin;
        box.hi = c + vec3(r) + margin;
    } else {
        for (int k = 0; k < 3; ++k)
            box.grow(vec3(p.v[3 * k], p.v[3 * k + 1], p.v[3 * k + 2]));
    }
    return box;
}

/// A hit on a packed primitive: t, the barycentrics (triangles only), the
/// primitive's number in scene order (without sphere_flag) and, for a
/// triangle, where its corners were read: coordinate j (a.x a.y a.z b.x ...)
/// at corners[j * stride] (a packed_primitive: stride 1; a lane of a
/// triangle_block: stride 4). They are in cache: completing the hit record
/// reads them there rather than through the mesh's index arrays. A BVH also
/// gives the triangle's normal, triangle_normal of those corners computed
/// when it was built (else normal is null).
struct primitive_hit {
    real t = 0;
    real b0 = 0, b1 = 0, b2 = 0;
    std::uint32_t id = 0;
    const real* corners = nullptr;
    int stride = 1;
    const vec3* normal = nullptr;
};

/// The one rule for "closest": a smaller t wins; at an equal t the later
/// primitive in scene order wins, as in the course's list loop, which passes
/// the closest t so far as tmax and so accepts a later hit at the same t.
/// With it the flat list and the BVH return the same hit whatever the order
/// of their tests.
inline bool replaces(real t, std::uint32_t id, const primitive_hit& best)
{
    return t < best.t || (t == best.t && id > best.id);
}

/// The same rule for a whole candidate hit.
inline bool replaces(const primitive_hit& candidate, const primitive_hit& best)
{
    return replaces(candidate.t, candidate.id, best);
}

namespace detail {

/// Intersects one packed primitive with the library's default methods: the
/// watertight triangle test and rt::hit_sphere.
inline bool intersect_packed(const packed_primitive& p, const ray& r, const watertight_ray& w, real tmin, real tmax,
                             primitive_hit& hit)
{
    if (p.id & sphere_flag) {
        sphere s;
        s.center = vec3(p.v[0], p.v[1], p.v[2]);
        s.radius = p.v[3];
        hit_record rec;
        if (!hit_sphere(s, r, tmin, tmax, rec))
            return false;
        hit.t = rec.t;
        hit.b0 = hit.b1 = hit.b2 = 0;
        hit.id = p.id & ~sphere_flag;
        hit.corners = nullptr;
        return true;
    }
    triangle_hit h;
    if (!intersect_watertight(w, p.v, tmin, tmax, h))
        return false;
    hit.t = h.t;
    hit.b0 = h.b0;
    hit.b1 = h.b1;
    hit.b2 = h.b2;
    hit.id = p.id;
    hit.corners = p.v;
    hit.stride = 1;
    return true;
}

} // namespace detail

/// The flat list over packed primitives: every primitive tested, the closest
/// kept by replaces(). For scenes too small to pay for a BVH.
inline bool closest_hit_flat(const std::vector<packed_primitive>& prims, const ray& r, real tmin, real tmax,
                         primitive_hit& best)
{
    const watertight_ray w = make_watertight_ray(r);
    bool found = false;
    for (const packed_primitive& p : prims) {
        primitive_hit h;
        if (detail::intersect_packed(p, r, w, tmin, found ? best.t : tmax, h) && (!found || replaces(h, best))) {
            best = h;
            found = true;
        }
    }
    return found;
}

/// Whether any packed primitive is hit in [tmin, tmax].
inline bool any_hit_flat(const std::vector<packed_primitive>& prims, const ray& r, real tmin, real tmax)
{
    const watertight_ray w = make_watertight_ray(r);
    primitive_hit h;
    for (const packed_primitive& p : prims)
        if (detail::intersect_packed(p, r, w, tmin, tmax, h))
            return true;
    return false;
}

} // namespace rt
