// reintersect.hpp - pbrt's reintersection measurement, restated in rt
// (tests/library_reintersect.cpp asserts and prints it, tests/docs_figures.cpp
// quotes it in docs/stages/06-going-further.md): one copy of the code, so the
// page, the printed tables and the assertions cannot disagree. No doctest here
// (docs_figures is a plain program).
//
// The method is pbrt-v4's shape test (Pharr, Jakob, Humphreys, pbrt-v4,
// src/pbrt/shapes_test.cpp, TEST(Triangle, Reintersect)), restated in rt's
// own code against its public API: see library_reintersect.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include <rt/bvh/accelerator.hpp>
#include <rt/core/hit_record.hpp>
#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/intersection/offset.hpp>
#include <rt/core/random.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/scene.hpp>
#include <rt/intersection/spawn.hpp>
#include <rt/core/vec.hpp>

namespace rt_test::reintersect {


using rt::real;
using rt::vec3;

inline constexpr bool in_float = sizeof(real) == 4;

/// pbrt's coordinate law: 10^e, e uniform in [-8, 8].
inline double random_magnitude(rt::pcg32& g)
{
    const double u = g.next_float();
    return std::pow(10.0, -8.0 + 16.0 * u);
}

inline vec3 random_point(rt::pcg32& g)
{
    const double x = random_magnitude(g);
    const double y = random_magnitude(g);
    const double z = random_magnitude(g);
    return vec3(real(x), real(y), real(z));
}

/// A uniform direction on the unit sphere (Archimedes: z uniform in [-1, 1],
/// the azimuth uniform), computed in double.
inline vec3 random_direction(rt::pcg32& g)
{
    const double u = g.next_float();
    const double v = g.next_float();
    const double z = 1 - 2 * u;
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    const double phi = 2 * 3.14159265358979323846 * v;
    return vec3(real(r * std::cos(phi)), real(r * std::sin(phi)), real(z));
}

struct dvec {
    double x, y, z;
};
inline dvec to_d(const vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
inline dvec sub(const dvec& a, const dvec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline double dot(const dvec& a, const dvec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double length(const dvec& a) { return std::sqrt(dot(a, a)); }

/// One row of the tables: rays traced and how many came back to their surface.
struct tally {
    long rays = 0, failures = 0;
    void add(bool failed)
    {
        ++rays;
        failures += failed ? 1 : 0;
    }
};

/// The rows, in the order of the table (docs/stages/06-shadows.md).
enum row {
    spawn_random,        // rt::spawn_ray, a random direction
    spawn_to_point,      // rt::spawn_ray_to, a random point, segment [0, 1]
    pbr_to_point,        // PBR's offset towards the point without the grazing cases (issue 19's "before")
    rtg_front,           // Ray Tracing Gems offset, random directions on the front side
    rtg_to_point,        // Ray Tracing Gems offset towards a point, segment [0, 1]
    shadow_robust,       // the stage-06 shadow ray: rt::spawn_ray_to the light, t < 1 - shadow_epsilon
    shadow_rtg,          // the stage-06 shadow ray before issue 19: Ray Tracing Gems offset, t < 0.9999 distance
    mirror_robust,       // the stage-07 mirror ray: rt::spawn_ray of the reflected direction
    mirror_rtg,          // the stage-07 mirror ray before issue 19: Ray Tracing Gems offset
    row_count
};

inline const char* const row_names[row_count] = {
    "spawn_ray, random direction",
    "spawn_ray_to a point, segment end 1",
    "PBR offset to a point, no grazing care",
    "Ray Tracing Gems offset, front side",
    "Ray Tracing Gems offset to a point",
    "shadow ray (light_visible) to a light",
    "shadow ray, Ray Tracing Gems offset",
    "mirror ray (ray_color)",
    "mirror ray, Ray Tracing Gems offset",
};

/// Whether each row is one of the renderer's methods, which must never fail.
inline const bool row_is_robust[row_count] = {true, true, false, false, false, true, false, true, false};

inline std::string table_of(const char* title, const tally rows[row_count], long shapes, long hits)
{
    std::string text = std::string(title) + " (" + (in_float ? "float" : "double") + "): " + std::to_string(shapes) +
                       " shapes, " + std::to_string(hits) + " hits\n";
    for (int k = 0; k < row_count; ++k) {
        char line[160];
        std::snprintf(line, sizeof line, "  %-42s %8ld of %9ld\n", row_names[k], rows[k].failures, rows[k].rays);
        text += line;
    }
    return text;
}

/// The Ray Tracing Gems origin on the side of the normal where `towards` lies.
inline vec3 rtg_origin(const rt::hit_record& rec, const vec3& towards)
{
    const vec3& n = rec.geometric_normal;
    return rt::offset_ray_origin(rec.point, glm::dot(towards, n) < 0 ? -n : n);
}

/// The rays of every row from one hit `rec` of the primary ray `primary` on
/// the only shape of `world`. `leaves(w)` says whether the exact ray from the
/// hit in direction w cannot meet the shape again (always, for a triangle),
/// `clear_of(T)` the same for the segment to the point T.
template <class Leaves, class ClearOf>
void spawn_from(const rt::accelerator& world, const rt::ray& primary, const rt::hit_record& rec, rt::pcg32& g,
                int rays, Leaves&& leaves, ClearOf&& clear_of, tally rows[row_count])
{
    const rt::real inf = rt::infinity;
    for (int j = 0; j < rays; ++j) {
        const vec3 w = random_direction(g);
        if (leaves(w)) {
            rows[spawn_random].add(world.any_hit(rt::spawn_ray(rec, w), 0, inf));
            if (glm::dot(w, rec.geometric_normal) > 0)
                rows[rtg_front].add(world.any_hit(rt::ray{rtg_origin(rec, w), w}, 0, inf));
        }

        const vec3 target = random_point(g);
        if (clear_of(target)) {
            rows[spawn_to_point].add(world.any_hit(rt::spawn_ray_to(rec, target), 0, 1));
            const vec3 pbr = rt::detail::offset_past_error_bounds(rec.point, rec.point_error, rec.geometric_normal, target - rec.point);
            rows[pbr_to_point].add(world.any_hit(rt::ray{pbr, target - pbr}, 0, 1));
            const vec3 rtg = rtg_origin(rec, target - rec.point);
            rows[rtg_to_point].add(world.any_hit(rt::ray{rtg, target - rtg}, 0, 1));

            // a point light at the target, asked as direct_lighting asks it
            // (only a light on the outer side of the geometric normal)
            rt::light bulb;
            bulb.position = target;
            const rt::light_sample sample = rt::sample_light(bulb, rec.point);
            if (glm::dot(rec.geometric_normal, sample.l) > 0 && sample.distance > 0) {
                // what light_visible does (include/rt/shading/shadows.hpp)
                const rt::ray shadow = rt::spawn_ray_to(rec, rec.point + sample.distance * sample.l);
                rows[shadow_robust].add(world.any_hit(shadow, 0, 1 - rt::shadow_epsilon));
                // what it did before issue 19
                const rt::ray old{rt::offset_ray_origin(rec.point, rec.geometric_normal), sample.l};
                rows[shadow_rtg].add(world.any_hit(old, 0, sample.distance * (1 - real(1e-4))));
            }
        }

        // a mirror ray, as ray_color makes it (reflect, include/rt/shading/raytracer.hpp,
        // written out: the library suites call no exercise), of the primary ray
        // and of random rays arriving on the side the primary ray came from
        vec3 incoming = j == 0 ? primary.direction : random_direction(g);
        if (glm::dot(incoming, rec.geometric_normal) > 0)
            incoming = -incoming;
        const vec3 m = incoming - 2 * glm::dot(incoming, rec.normal) * rec.normal;
        if (leaves(m)) {
            rows[mirror_robust].add(world.any_hit(rt::spawn_ray(rec, m), 0, inf));
            rows[mirror_rtg].add(
                world.any_hit(rt::ray{rt::offset_ray_origin(rec.point, rec.geometric_normal), m}, 0, inf));
        }
    }
}

inline rt::scene scene_of(const rt::shape& item)
{
    rt::scene s;
    s.shapes.push_back(item);
    return s;
}

/// The tallies of one kind of shape: every row, and how the shapes fared.
struct reintersection {
    tally rows[row_count];
    long shapes = 0, hits = 0;
    long refused = 0;            ///< spheres smaller than the rounding of their centre (the loader refuses them)
    long non_finite_normals = 0; ///< hits whose geometric normal is not finite (never, the test asserts)
};

/// pbrt's test on `shapes` random triangles, `rays` rays from each hit.
inline reintersection triangles(int shapes, int rays)
{
    reintersection result;
    result.shapes = shapes;
    tally* rows = result.rows;
    for (int i = 0; i < shapes; ++i) {
        rt::pcg32 g(std::uint64_t(i), 19);
        rt::triangle tri;
        tri.a = random_point(g);
        tri.b = random_point(g);
        tri.c = random_point(g);
        // aim at a uniform point of the triangle (barycentrics by the square
        // root method, PBR 3rd ed. sec. 13.6.5), computed in double
        const double u0 = g.next_float();
        const double u1 = g.next_float();
        const double su = std::sqrt(u0), b0 = 1 - su, b1 = u1 * su, b2 = 1 - b0 - b1;
        const dvec a = to_d(tri.a), b = to_d(tri.b), c = to_d(tri.c);
        const vec3 aim(real(b0 * a.x + b1 * b.x + b2 * c.x), real(b0 * a.y + b1 * b.y + b2 * c.y),
                       real(b0 * a.z + b1 * b.z + b2 * c.z));
        const vec3 from = random_point(g);
        const rt::ray primary{from, aim - from};
        const rt::scene s = scene_of(tri);
        const rt::accelerator world(s);
        rt::hit_record rec;
        if (!world.closest_hit(primary, 0, rt::infinity, rec))
            continue; // rounding can make the aimed ray miss (pbrt's test skips these too)
        ++result.hits;
        if (!std::isfinite(rec.geometric_normal.x))
            ++result.non_finite_normals;
        spawn_from(
            world, primary, rec, g, rays, [](const vec3&) { return true; }, [](const vec3&) { return true; }, rows);
    }
    return result;
}

/// The same on `shapes` random spheres.
inline reintersection spheres(int shapes, int rays)
{
    reintersection result;
    result.shapes = shapes;
    tally* rows = result.rows;
    for (int i = 0; i < shapes; ++i) {
        rt::pcg32 g(std::uint64_t(i), 23);
        rt::sphere ball;
        ball.center = random_point(g);
        ball.radius = real(random_magnitude(g));
        if (!rt::sphere_fits_its_position(ball)) {
            ++result.refused; // the scene loader refuses these (see the last cases)
            continue;
        }
        const vec3 aim = ball.center + ball.radius * random_direction(g);
        const vec3 from = random_point(g);
        const rt::ray primary{from, aim - from};
        const rt::scene s = scene_of(ball);
        const rt::accelerator world(s);
        rt::hit_record rec;
        if (!world.closest_hit(primary, 0, rt::infinity, rec))
            continue;
        ++result.hits;
        if (!std::isfinite(rec.geometric_normal.x))
            ++result.non_finite_normals;
        // The true hit point, in long double from the float ray and sphere
        // (the rounded rec.point of a sphere only a few ulps of its centre
        // across is too coarse to say which rays leave it), and which rays
        // leave by a clear margin: the exact ray from a point of a sphere meets
        // it again only when it points inwards (cosine with the outward normal
        // below 0). The primary ray hits the first root at t >= 0.
        using ld = long double;
        const ld f[3] = {ld(from.x) - ld(ball.center.x), ld(from.y) - ld(ball.center.y), ld(from.z) - ld(ball.center.z)};
        const ld d[3] = {ld(primary.direction.x), ld(primary.direction.y), ld(primary.direction.z)};
        const ld qa = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        const ld qb = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
        const ld qc = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - ld(ball.radius) * ld(ball.radius);
        // the discriminant from the centre's perpendicular to the line (Ray
        // Tracing Gems ch. 7): b^2 - a c itself cancels far from the sphere
        const ld dl = std::sqrt(qa);
        const ld along = qb / dl;
        const ld l[3] = {f[0] - along * d[0] / dl, f[1] - along * d[1] / dl, f[2] - along * d[2] / dl};
        const ld R2 = ld(ball.radius) * ld(ball.radius);
        const ld root = std::sqrt(std::max(ld(0), qa * (R2 - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]))));
        const ld q = -(qb + (qb < 0 ? -root : root));
        const ld t0 = q != 0 ? qc / q : ld(0), t1 = q / qa;
        const ld t = std::min(t0, t1) >= 0 ? std::min(t0, t1) : std::max(t0, t1); // the first root at t >= 0
        const dvec out = {double((f[0] + t * d[0]) / ld(ball.radius)), double((f[1] + t * d[1]) / ld(ball.radius)),
                          double((f[2] + t * d[2]) / ld(ball.radius))};
        const dvec p = {double(ld(ball.center.x) + ld(ball.radius) * ld(out.x)),
                        double(ld(ball.center.y) + ld(ball.radius) * ld(out.y)),
                        double(ld(ball.center.z) + ld(ball.radius) * ld(out.z))};
        const double margin = 1e-3;
        auto leaves = [&](const vec3& w) { return dot(out, to_d(w)) > margin * length(to_d(w)); };
        auto clear_of = [&](const vec3& target) {
            const dvec to = sub(to_d(target), p);
            return dot(out, to) > margin * length(to);
        };
        spawn_from(world, primary, rec, g, rays, leaves, clear_of, rows);
    }
    return result;
}

/// Rays leaving a triangle whose points have coordinates of mixed magnitudes.
struct mixed_result {
    tally rtg, robust; ///< the Ray Tracing Gems offset, rt::spawn_ray
};

inline mixed_result mixed_magnitudes()
{
    // A plane tilted by about 3e-5 out of x = const, at y, z near 1e7 and x
    // near 0.08 (issue 19 found p = (0.0847, 1.3e7, 2.6e7)). The offset of Ray
    // Tracing Gems moves x by 256 of x's own ulps (ulp(0.08) = 7.5e-9: 1.9e-6)
    // and y, z by int(256 n_y) = 0 ulps, while the hit point's error in y and z
    // is whole units, which the tilt turns into about 1e-4 along the normal.
    const rt::triangle tri{{real(0.001), real(1e7), real(3e7)}, {real(300), real(2e7), real(2e7)},
                           {real(0.05), real(5e6), real(2.5e7)}, -1};
    const rt::scene s = scene_of(tri);
    const rt::accelerator world(s);
    rt::pcg32 g(7, 19);
    mixed_result result;
    tally& rtg = result.rtg;
    tally& robust = result.robust;
    for (int k = 0; k < 20000; ++k) {
        // a point of the triangle near its edge a-c, where x is small
        const double u = g.next_float();
        const double v = g.next_float();
        const double b1 = 1e-9 * v, b2 = u * (1 - b1), b0 = 1 - b1 - b2;
        const vec3 aim(real(b0 * 0.001 + b1 * 300 + b2 * 0.05), real(b0 * 1e7 + b1 * 2e7 + b2 * 5e6),
                       real(b0 * 3e7 + b1 * 2e7 + b2 * 2.5e7));
        const vec3 from = aim + real(1e6) * random_direction(g);
        rt::hit_record rec;
        if (!world.closest_hit(rt::ray{from, aim - from}, 0, rt::infinity, rec))
            continue;
        vec3 w = random_direction(g);
        if (glm::dot(w, rec.geometric_normal) < 0)
            w = -w;
        rtg.add(world.any_hit(rt::ray{rt::offset_ray_origin(rec.point, rec.geometric_normal), w}, 0, rt::infinity));
        robust.add(world.any_hit(rt::spawn_ray(rec, w), 0, rt::infinity));
    }
    return result;
}

} // namespace rt_test::reintersect
