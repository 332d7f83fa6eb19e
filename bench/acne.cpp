// Experiment 5: self-intersection, acne fraction against scene scale, fixed
// epsilon vs the Ray Tracing Gems offset vs the error-bounded spawn.
//
// The scene: a unit sphere resting on a ground plane (two triangles), a point
// light above, a camera in front; every coordinate multiplied by a scale S =
// 1e-4 ... 1e5. Each primary hit (rt::accelerator::closest_hit) gets a shadow
// ray to the light five ways:
//   no_offset      from the hit point itself, t in [0, ...): the naive ray;
//   fixed_epsilon  rt::light_visible_fixed_epsilon (t >= 1e-4, the textbook's);
//   rtg_offset     from rt::offset_ray_origin(p, n_g) (Ray Tracing Gems ch. 6,
//                  the offset stage 06 teaches; rt::light_visible used it
//                  before issue 19; this CSV row was called robust_offset then),
//                  t up to the light's distance times 1 - 1e-4;
//   error_bounds   rt::spawn_ray (PBR 3rd ed. sec. 3.9.5: past the hit point's
//                  rounding error bound) along the direction to the light,
//                  t up to the distance from the spawned origin times 1 - 1e-4;
//   light_visible  rt::light_visible itself: since issue 19 the segment of
//                  rt::spawn_ray_to (the same error bound, the side decided
//                  robustly for grazing rays), t in [0, 1 - shadow_epsilon).
// The truth comes from the analytic scene in double: a ground point is in
// shadow exactly when its segment to the light passes through the sphere; a
// sphere point is lit exactly when its outward normal faces the light (the
// plane is below every such segment). Points within 1e-3 of either boundary
// (relative) are left out as ambiguous.
//   acne = lit points reported in shadow / lit points;
//   leak = shadowed points reported lit / shadowed points.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/camera/camera.hpp>
#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/intersection/offset.hpp>
#include <rt/scene/scene.hpp>
#include <rt/shading/shadows.hpp>
#include <rt/intersection/spawn.hpp>

#include "bench.hpp"

namespace {

using rt::real;
using rt::vec3;

struct dvec {
    double x, y, z;
};

dvec to_d(const vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
double dot(const dvec& a, const dvec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
dvec sub(const dvec& a, const dvec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

enum class truth { lit, shadowed, ambiguous };

constexpr int methods = 5;

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_acne", [&] {
        const bench::options o = bench::parse_options(argc, argv, "bench_acne: experiment 5, self-intersection");
        const int width = o.quick ? 64 : 480, height = o.quick ? 48 : 360;
        bench::csv table("self-intersection: acne and leaks against scene scale (bench/acne.cpp)",
                         {"scale", "method", "lit_points", "shadowed_points", "ambiguous_points", "acne",
                          "acne_fraction", "leaks", "leak_fraction"});
        table.note("scene", "unit sphere on a ground plane (2 triangles), point light above; everything times the scale");
        table.note("image", std::to_string(width) + "x" + std::to_string(height) + " primary rays");

        for (int e = -4; e <= 5; ++e) {
            const real S = real(std::pow(10.0, e));
            rt::scene s;
            const real g = 10 * S; // the ground's half size
            s.shapes.emplace_back(rt::triangle{vec3(-g, 0, -g), vec3(-g, 0, g), vec3(g, 0, g), -1});
            s.shapes.emplace_back(rt::triangle{vec3(-g, 0, -g), vec3(g, 0, g), vec3(g, 0, -g), -1});
            s.shapes.emplace_back(rt::sphere{vec3(0, S, 0), S, -1});
            rt::light lamp;
            lamp.kind = rt::light_kind::point;
            lamp.position = S * vec3(3, 6, 2);
            rt::camera cam;
            cam.eye = S * vec3(0, 3, 8);
            cam.look_at = S * vec3(0, real(0.5), 0);
            cam.fov_degrees = 50;
            const rt::accelerator accel(s, rt::accelerator_kind::automatic);
            const rt::ray_generator gen = rt::make_ray_generator(cam, width, height);

            const dvec centre{0, double(S), 0}, light_d = to_d(lamp.position);
            const double R = double(S);
            std::size_t lit = 0, shadowed = 0, ambiguous = 0;
            std::size_t acne[methods] = {}, leaks[methods] = {};
            for (int j = 0; j < height; ++j)
                for (int i = 0; i < width; ++i) {
                    const rt::ray r = rt::pixel_ray(gen, i, j);
                    rt::hit_record hit;
                    if (!accel.closest_hit(r, real(0), std::numeric_limits<real>::infinity(), hit))
                        continue;
                    // the truth at the true surface point nearest the computed one
                    truth t = truth::ambiguous;
                    const dvec p = to_d(hit.point);
                    if (hit.shape == 2) {
                        const dvec n = sub(p, centre);
                        const double len = std::sqrt(dot(n, n));
                        const dvec unit{n.x / len, n.y / len, n.z / len};
                        const dvec on{centre.x + R * unit.x, centre.y + R * unit.y, centre.z + R * unit.z};
                        const dvec l = sub(light_d, on);
                        const double cosine = dot(unit, l) / std::sqrt(dot(l, l));
                        t = cosine > 1e-3 ? truth::lit : cosine < -1e-3 ? truth::shadowed : truth::ambiguous;
                        if (t == truth::shadowed)
                            continue; // the light is behind the surface: shading sends no shadow ray there
                    } else {
                        const dvec on{p.x, 0, p.z};
                        const dvec l = sub(light_d, on);
                        // the distance from the sphere's centre to the segment on -> light
                        const double u = std::max(0.0, std::min(1.0, dot(sub(centre, on), l) / dot(l, l)));
                        const dvec closest{on.x + u * l.x, on.y + u * l.y, on.z + u * l.z};
                        const dvec gap = sub(centre, closest);
                        const double distance = std::sqrt(dot(gap, gap));
                        t = distance > R * (1 + 1e-3)   ? truth::lit
                            : distance < R * (1 - 1e-3) ? truth::shadowed
                                                        : truth::ambiguous;
                    }
                    if (t == truth::ambiguous) {
                        ++ambiguous;
                        continue;
                    }
                    (t == truth::lit ? lit : shadowed)++;
                    const rt::light_sample sample = rt::sample_light(lamp, hit.point);
                    const real tmax = sample.distance * (1 - real(1e-4));
                    const rt::ray rtg{rt::offset_ray_origin(hit.point, hit.geometric_normal), sample.l};
                    const rt::ray spawned = rt::spawn_ray(hit, sample.l);
                    const real spawned_tmax = glm::length(lamp.position - spawned.origin) * (1 - real(1e-4));
                    const bool visible[methods] = {
                        !accel.any_hit(rt::ray{hit.point, sample.l}, real(0), tmax),
                        rt::light_visible_fixed_epsilon(accel, hit, sample),
                        !accel.any_hit(rtg, real(0), tmax),
                        !accel.any_hit(spawned, real(0), spawned_tmax),
                        rt::light_visible(accel, hit, sample)};
                    for (int m = 0; m < methods; ++m) {
                        if (t == truth::lit && !visible[m])
                            ++acne[m];
                        if (t == truth::shadowed && visible[m])
                            ++leaks[m];
                    }
                }
            const char* names[methods] = {"no_offset", "fixed_epsilon", "rtg_offset", "error_bounds",
                                          "light_visible"};
            for (int m = 0; m < methods; ++m) {
                const double af = lit ? double(acne[m]) / double(lit) : 0;
                const double lf = shadowed ? double(leaks[m]) / double(shadowed) : 0;
                table.row() << double(S) << names[m] << lit << shadowed << ambiguous << acne[m] << af << leaks[m] << lf;
                std::cout << "scale " << double(S) << ", " << names[m] << ": acne " << af << ", leaks " << lf << '\n';
            }
        }
        table.write(o, "acne.csv");
        return 0;
    });
}
