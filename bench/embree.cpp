// Experiment 6: rt's BVH against Embree 3, the same rays in the same run.
//
// For every mesh of ../shared/meshes (a mesh that is absent is skipped with a
// message), both engines get the same triangles and the same rays:
//   outside    primary rays from a camera outside the model, looking at it
//              (row by row through pixel centres: coherent);
//   centre     primary rays from the centre of the bounding box, 90 degree field of view;
//   shadow     from each hit of those two sets to a light (any hit): the
//              segment rt::spawn_ray_to gives, traced in [0, 1 - shadow_epsilon),
//              as rt::light_visible traces it (since issue 19; before, the rays
//              started at rt::offset_ray_origin, the Ray Tracing Gems offset).
//              Its hit record is rt's own (rt::fill_triangle_record) at
//              Embree's hit, from Embree's barycentrics: the point, its
//              rounding error bound and rt::triangle_normal;
//   shadow-surface  the same lights from the same hits, but as a simple
//              tracer sends them: from the hit point o + t d itself (Embree's
//              t, no offset), towards the light, the direction not normalised
//              (t = 1 at the light), traced in [1e-4, 1]: every ray starts on
//              a surface and only t_min keeps it off its own triangle;
//   incoherent from uniform random points of the bounding sphere to uniform
//              random points of the box.
// rt uses its scene-level accelerator (rt::accelerator, kind bvh: closest_hit
// and any_hit), Embree rtcIntersect1 and rtcOccluded1 (single rays, the same
// calling pattern as rt's) on a scene of default build quality. We report
// build time (Embree with one thread and with all, and with one thread at high
// quality, the build with spatial splits as rt's default), rays per second on one
// thread and on all, hit counts, the rays on which the two disagree, and the
// ratio rt / Embree. Timings are the best of a few runs, taken alternately
// (rt, Embree, rt, Embree, ...) so that both see the same machine.
#include <embree3/rtcore.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <rt/camera/camera.hpp>
#include <rt/input/obj_loader.hpp>
#include <rt/core/random.hpp>
#include <rt/scene/scene.hpp>
#include <rt/intersection/spawn.hpp>
#include <rt/intersection/watertight.hpp>
#if defined(RT_BENCH_HAS_ACCELERATOR)
#include <rt/bvh/accelerator.hpp>
#endif

#include "bench.hpp"
#include "embree_scene.hpp"

#ifndef RT_BENCH_EMBREE_VERSION
#define RT_BENCH_EMBREE_VERSION RTC_VERSION_STRING
#endif

namespace {

using rt::real;
using rt::vec3;
using bench::embree_scene;
constexpr float infinity = std::numeric_limits<float>::infinity();

/// A set of rays: origins, unit directions and segment ends.
struct ray_set {
    std::string name;
    bool shadow = false;  ///< any hit (occlusion) instead of closest hit
    float tmin = 0;       ///< every ray's segment starts here
    std::vector<rt::ray> rays;
    std::vector<float> tmax;
    std::vector<unsigned> source;  ///< shadow rays: the triangle the ray starts on
};

/// What one engine answers for one ray: t of the closest hit (infinity on a
/// miss) or, for shadow rays, 0 when occluded and infinity when not.
using answers = std::vector<float>;

struct model {
    std::string file;
    rt::mesh geometry;
    rt::aabb box;
};

/// Primary rays of a pinhole camera through the pixel centres, row by row.
ray_set primary(const std::string& name, const vec3& eye, const vec3& look_at, real fov, int width, int height)
{
    rt::camera cam;
    cam.eye = eye;
    cam.look_at = look_at;
    cam.up = std::fabs(glm::normalize(look_at - eye).y) > real(0.99) ? vec3(0, 0, 1) : vec3(0, 1, 0);
    cam.fov_degrees = fov;
    const rt::ray_generator gen = rt::make_ray_generator(cam, width, height);
    ray_set set;
    set.name = name;
    for (int j = height - 1; j >= 0; --j)
        for (int i = 0; i < width; ++i) {
            rt::ray r = rt::pixel_ray(gen, i, j);
            r.direction = glm::normalize(r.direction);
            set.rays.push_back(r);
            set.tmax.push_back(infinity);
        }
    return set;
}

ray_set incoherent(const model& m, std::size_t count)
{
    ray_set set;
    set.name = "incoherent";
    const vec3 centre = m.box.center();
    const real radius = real(0.5) * glm::length(m.box.extent());
    rt::pcg32 rng(2024, 11);
    auto uniform = [&] { return real(rng.next_float()); };
    while (set.rays.size() < count) {
        // a uniform point of the sphere: z uniform in [-1, 1], angle uniform
        const real z = 2 * uniform() - 1, phi = real(6.283185307179586) * uniform();
        const real s = std::sqrt(std::max(real(0), 1 - z * z));
        const vec3 origin = centre + radius * vec3(s * std::cos(phi), s * std::sin(phi), z);
        const vec3 target = m.box.lo + vec3{uniform(), uniform(), uniform()} * m.box.extent();
        const vec3 d = target - origin;
        if (glm::dot(d, d) == 0)
            continue;
        set.rays.push_back(rt::ray{origin, glm::normalize(d)});
        set.tmax.push_back(infinity);
    }
    return set;
}

/// Shadow rays from the hits of `from` (found by Embree) towards `light`, as
/// rt::light_visible sends them: the segment of rt::spawn_ray_to (t = 1 at the
/// light), up to 1 - rt::shadow_epsilon.
void add_shadow_rays(ray_set& shadow, const ray_set& from, const embree_scene& embree, const rt::mesh& g,
                     const vec3& light)
{
    for (const rt::ray& r : from.rays) {
        float t = 0, u = 0, v = 0;
        unsigned triangle = 0;
        vec3 n;
        if (!embree.closest_with_normal(r, infinity, t, triangle, n, u, v))
            continue;
        auto corner = [&](int c) { return g.positions[g.triangles[triangle][std::size_t(c)]]; };
        rt::triangle_hit h;
        h.t = real(t);
        h.b0 = 1 - real(u) - real(v);
        h.b1 = real(u);
        h.b2 = real(v);
        rt::hit_record rec;
        rt::fill_triangle_record(corner(0), corner(1), corner(2), r, h, rec);
        if (!(glm::length(light - rec.point) > 0))
            continue;
        shadow.rays.push_back(rt::spawn_ray_to(rec, light));
        shadow.tmax.push_back(float(real(1) - rt::shadow_epsilon));
        shadow.source.push_back(triangle);
    }
}

/// Shadow rays from the hits of `from` (found by Embree) towards `light` as a
/// simple tracer sends them: from o + t d itself, the direction light - origin
/// (t = 1 at the light, not normalised); the set's tmin (1e-4) is all that
/// keeps a ray off the triangle it starts on.
void add_surface_shadow_rays(ray_set& shadow, const ray_set& from, const embree_scene& embree, const vec3& light)
{
    for (const rt::ray& r : from.rays) {
        float t = 0;
        unsigned triangle = 0;
        vec3 n;
        if (!embree.closest_with_normal(r, infinity, t, triangle, n))
            continue;
        const vec3 origin = r.origin + real(t) * r.direction;
        if (!(glm::length(light - origin) > 0))
            continue;
        shadow.rays.push_back(rt::ray{origin, light - origin});
        shadow.tmax.push_back(1.0f);
        shadow.source.push_back(triangle);
    }
}

/// Whether the ray truly meets the triangle a, b, c at 0 < t <= tmax:
/// Moller-Trumbore (1997) in long double on the float inputs, with a margin of
/// 1e-9 on the barycentrics so that edge ties do not count.
bool truly_hits(const rt::ray& r, const vec3& a, const vec3& b, const vec3& c, float tmax)
{
    using L = long double;
    const L o[3] = {r.origin.x, r.origin.y, r.origin.z}, d[3] = {r.direction.x, r.direction.y, r.direction.z};
    L e1[3], e2[3], s[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = L(b[k]) - a[k];
        e2[k] = L(c[k]) - a[k];
        s[k] = o[k] - a[k];
    }
    auto cross = [](const L* x, const L* y, L* z) {
        z[0] = x[1] * y[2] - x[2] * y[1];
        z[1] = x[2] * y[0] - x[0] * y[2];
        z[2] = x[0] * y[1] - x[1] * y[0];
    };
    auto dot = [](const L* x, const L* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    L p[3], q[3];
    cross(d, e2, p);
    const L det = dot(e1, p);
    if (det == 0)
        return false;
    cross(s, e1, q);
    const L u = dot(s, p) / det, v = dot(d, q) / det, t = dot(e2, q) / det;
    const L margin = 1e-9L;
    return u > margin && v > margin && u + v < 1 - margin && t > 0 && t <= tmax;
}

template <class Query>
double time_set(const ray_set& set, unsigned threads, int repeats, answers& out, Query&& query)
{
    out.assign(set.rays.size(), 0);
    return bench::best_time(repeats, [&] {
        bench::parallel_blocks(set.rays.size(), threads, 1024, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k)
                out[k] = query(set.rays[k], set.tmax[k]);
        });
    });
}

std::size_t count_hits(const answers& a)
{
    std::size_t n = 0;
    for (float t : a)
        n += t < infinity;
    return n;
}

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_embree", [&] {
        const bench::options o =
            bench::parse_options(argc, argv, "bench_embree: experiment 6, rt's BVH against Embree 3 on the shared meshes");
        const unsigned all = bench::hardware_threads();
        const int repeats = o.quick ? 1 : 5; // best of 5 rounds, the engines in turn: the machine is shared
        const int build_repeats = o.quick ? 1 : 9; // the builds: best of 9
        const int width = o.quick ? 64 : 1024, height = o.quick ? 48 : 768;
        const std::size_t incoherent_count = o.quick ? 4096 : std::size_t(1) << 20;
        // quick mode: the two small meshes only (loading the 1.1M-triangle bunny alone takes seconds)
        std::vector<std::string> files = {"stanford-bunny.obj", "bunny-loop2.obj", "conference.obj",
                                          "sibenik.obj", "sponza-dabrovic.obj", "CornellBox-Original.obj"};
        if (o.quick)
            files = {"stanford-bunny.obj", "CornellBox-Original.obj"};
        for (const std::string& only : o.extra) // a mesh name on the command line limits the run to it
            if (only.find(".obj") != std::string::npos)
                files = {only};

        bench::csv rays("rt's BVH against Embree " RT_BENCH_EMBREE_VERSION ": rays per second (bench/embree.cpp)",
                        {"mesh", "triangles", "set", "rays", "threads", "rt_seconds", "embree_seconds",
                         "rt_mrays_per_s", "embree_mrays_per_s", "ratio_rt_over_embree", "rt_hits", "embree_hits",
                         "hit_mismatch", "depth_mismatch"});
        bench::csv builds("rt's BVH against Embree " RT_BENCH_EMBREE_VERSION ": build time (bench/embree.cpp)",
                          {"mesh", "triangles", "dropped_degenerate", "rt_build_seconds_1_thread",
                           "rt_build_seconds_all_threads", "embree_build_seconds_1_thread",
                           "embree_build_seconds_all_threads", "ratio_rt_over_embree_1_thread",
                           "rt_speedup_all_threads", "rt_build_seconds_1_thread_without_spatial_splits",
                           "embree_build_seconds_1_thread_high_quality"});
        for (bench::csv* table : {&rays, &builds}) {
            table->note("embree", std::string("Embree ") + RT_BENCH_EMBREE_VERSION +
                                       " (Debian libembree-dev), rtcIntersect1 / rtcOccluded1, default build quality");
            table->note("triangles", "as rt::load_obj gives them (zero-area triangles dropped); both engines get the same");
            table->note("rays", "outside and centre " + std::to_string(width) + "x" + std::to_string(height) +
                                    " primary rays; shadow rays from their hits; " +
                                    std::to_string(incoherent_count) + " incoherent rays");
#if !defined(RT_BENCH_HAS_ACCELERATOR)
            table->note("rt", "rt::accelerator (include/rt/bvh/accelerator.hpp) not present in this tree: rt columns are nan");
#endif
        }

        const std::filesystem::path folder = o.shared / "meshes";
        for (const std::string& file : files) {
            const std::filesystem::path path = folder / file;
            if (!std::filesystem::exists(path)) {
                std::cout << "skipping " << path.string() << ": not found\n";
                continue;
            }
            model m;
            m.file = file;
            auto load_start = bench::clock::now();
            m.geometry = rt::load_obj(path).geometry;
            m.box = rt::bounds(m.geometry);
            std::cout << file << ": " << m.geometry.triangles.size() << " triangles, loaded in "
                      << bench::seconds_since(load_start) << " s\n";
            const std::size_t triangles = m.geometry.triangles.size();

            // builds: the six kinds in turn in every round, best of build_repeats
            // each, so that a slower spell of the shared machine falls on all
            // of them (the builds' differences are a few percent)
            double embree_build_1 = 1e300, embree_build_all = 1e300, embree_build_high = 1e300;
            const auto time_embree = [&](const char* config, RTCBuildQuality quality, double& best) {
                best = std::min(best, embree_scene(m.geometry, config, quality).build_seconds());
            };
            double rt_build = std::nan(""), rt_build_all = std::nan(""), rt_build_plain = std::nan("");
#if defined(RT_BENCH_HAS_ACCELERATOR)
            rt::scene rt_scene;
            rt_scene.shapes.push_back(m.geometry);
            // rt on one thread and on all, and without spatial splits (the
            // accelerator as a program makes it: the mesh packed, the tree
            // built, the blocks laid out)
            rt_build = rt_build_all = rt_build_plain = 1e300;
            rt::bvh_options one_thread, plain;
            one_thread.threads = 1;
            plain.threads = 1;
            plain.spatial_budget = 0; // what the spatial splits cost
            // Each tree is freed before the next build, as Embree's scenes
            // are: three trees alive at once made the later builds fault in
            // fresh pages (the bunny's two-thread build took 11.1-11.6 ms
            // instead of 9.8-10.3).
            const auto time_rt = [&](const rt::bvh_options& options, double& best) {
                const auto start = bench::clock::now();
                rt::accelerator probe(rt_scene, rt::accelerator_kind::bvh, options);
                best = std::min(best, bench::seconds_since(start));
                bench::keep(probe);
            };
#endif
            for (int k = 0; k < build_repeats; ++k) {
                time_embree("threads=1", RTC_BUILD_QUALITY_MEDIUM, embree_build_1);
                time_embree(nullptr, RTC_BUILD_QUALITY_MEDIUM, embree_build_all);
                // Embree's build with spatial splits, like rt's default (its own default has none)
                time_embree("threads=1", RTC_BUILD_QUALITY_HIGH, embree_build_high);
#if defined(RT_BENCH_HAS_ACCELERATOR)
                time_rt(one_thread, rt_build);
                time_rt(rt::bvh_options{}, rt_build_all);
                time_rt(plain, rt_build_plain);
#endif
            }
            embree_scene embree(m.geometry, "threads=1"); // traversal needs no TBB workers
#if defined(RT_BENCH_HAS_ACCELERATOR)
            const rt::accelerator accel(rt_scene, rt::accelerator_kind::bvh);
#endif
            builds.row() << file << triangles << m.geometry.dropped_degenerate << rt_build << rt_build_all
                         << embree_build_1 << embree_build_all << rt_build / embree_build_1 << rt_build / rt_build_all
                         << rt_build_plain << embree_build_high;
            std::cout << "  build: rt " << rt_build << " s (1 thread), " << rt_build_all << " s (" << all
                      << " threads), " << rt_build_plain << " s (1 thread, no spatial splits); Embree " << embree_build_1 << " s (1 thread), " << embree_build_all << " s ("
                      << all << " threads), " << embree_build_high << " s (1 thread, high quality: spatial splits)\n";

            // the rays
            const vec3 centre = m.box.center();
            const real radius = real(0.5) * glm::length(m.box.extent());
            std::vector<ray_set> sets;
            sets.push_back(primary("outside", centre + real(2.2) * radius * glm::normalize(vec3(0.35, 0.3, 1)),
                                   centre, 45, width, height));
            sets.push_back(primary("centre", centre, centre + vec3(1, real(-0.1), real(0.2)), 90, width, height));
            ray_set shadow;
            shadow.name = "shadow";
            shadow.shadow = true;
            // a light above and in front of the model for the outside view, one
            // inside the box, above the centre, for the centre view
            add_shadow_rays(shadow, sets[0], embree, m.geometry, centre + real(1.5) * radius * glm::normalize(vec3(-0.4, 1, 0.6)));
            add_shadow_rays(shadow, sets[1], embree, m.geometry,
                            centre + vec3(real(0.1), real(0.35), real(0.05)) * m.box.extent());
            sets.push_back(std::move(shadow));
            ray_set surface;
            surface.name = "shadow-surface";
            surface.shadow = true;
            surface.tmin = 1e-4f;
            add_surface_shadow_rays(surface, sets[0], embree, centre + real(1.5) * radius * glm::normalize(vec3(-0.4, 1, 0.6)));
            add_surface_shadow_rays(surface, sets[1], embree, centre + vec3(real(0.1), real(0.35), real(0.05)) * m.box.extent());
            sets.push_back(std::move(surface));
            sets.push_back(incoherent(m, incoherent_count));

            // Every set on one thread and on all, both engines in turn, in
            // each of `repeats` rounds, best of the rounds: a slow spell of the
            // shared machine then falls on one round of many sets, not on every
            // round of one (a set's five repeats in a row had once all been
            // 30% slow, for either engine)
            struct timing {
                answers rt_answer, embree_answer;
                double rt_seconds = std::nan(""), embree_seconds = 1e300;
            };
            const unsigned thread_counts[2] = {1u, all};
            std::vector<timing> timings(2 * sets.size());
            for (int k = 0; k < repeats; ++k)
                for (std::size_t s = 0; s < sets.size(); ++s)
                    for (std::size_t q = 0; q < 2; ++q) {
                        const ray_set& set = sets[s];
                        const unsigned threads = thread_counts[q];
                        timing& out = timings[2 * s + q];
#if defined(RT_BENCH_HAS_ACCELERATOR)
                        double t;
                        if (set.shadow)
                            t = time_set(set, threads, 1, out.rt_answer, [&](const rt::ray& r, float tmax) {
                                return accel.any_hit(r, real(set.tmin), real(tmax)) ? 0.0f : infinity;
                            });
                        else
                            t = time_set(set, threads, 1, out.rt_answer, [&](const rt::ray& r, float tmax) {
                                rt::hit_record rec;
                                return accel.closest_hit(r, real(set.tmin), real(tmax), rec) ? float(rec.t) : infinity;
                            });
                        out.rt_seconds = k == 0 ? t : std::min(out.rt_seconds, t);
#endif
                        double e;
                        if (set.shadow)
                            e = time_set(set, threads, 1, out.embree_answer, [&](const rt::ray& r, float tmax) {
                                return embree.occluded(r, set.tmin, tmax) ? 0.0f : infinity;
                            });
                        else
                            e = time_set(set, threads, 1, out.embree_answer, [&](const rt::ray& r, float tmax) {
                                return embree.closest(r, set.tmin, tmax);
                            });
                        out.embree_seconds = std::min(out.embree_seconds, e);
                    }
            for (std::size_t s = 0; s < sets.size(); ++s) {
                for (std::size_t q = 0; q < 2; ++q) {
                    const ray_set& set = sets[s];
                    const unsigned threads = thread_counts[q];
                    const answers &rt_answer = timings[2 * s + q].rt_answer,
                                  &embree_answer = timings[2 * s + q].embree_answer;
                    const double rt_seconds = timings[2 * s + q].rt_seconds,
                                 embree_seconds = timings[2 * s + q].embree_seconds;
                    std::size_t hit_mismatch = 0, depth_mismatch = 0;
                    if (!rt_answer.empty())
                        for (std::size_t k = 0; k < set.rays.size(); ++k) {
                            const float a = rt_answer[k], b = embree_answer[k];
                            if ((a < infinity) != (b < infinity))
                                ++hit_mismatch;
                            else if (a < infinity && std::fabs(a - b) > 1e-4f * std::max(1.0f, std::fabs(b)))
                                ++depth_mismatch;
                        }
                    // shadow rays on which the two disagree: does Embree's occluder
                    // lie on the triangle the ray starts from (self-intersection)?
                    std::size_t embree_self = 0, embree_coplanar = 0, real_occluder = 0, embree_only = 0, rt_only = 0;
                    std::vector<std::string> examples; // distance / scene radius of the other occluders
                    if (set.shadow && !rt_answer.empty())
                        for (std::size_t k = 0; k < set.rays.size(); ++k) {
                            const bool rt_blocked = rt_answer[k] < infinity, embree_blocked = embree_answer[k] < infinity;
                            if (rt_blocked == embree_blocked)
                                continue;
                            if (rt_blocked) {
                                ++rt_only;
                                continue;
                            }
                            ++embree_only;
                            float t = 0;
                            unsigned triangle = 0;
                            vec3 normal;
                            if (!embree.closest_with_normal(set.rays[k], set.tmax[k], t, triangle, normal, set.tmin))
                                continue;
                            if (triangle == set.source[k]) {
                                ++embree_self;
                                continue;
                            }
                            // another triangle: is it in the plane of the one the ray starts on
                            // (overlapping, coplanar geometry), and how far along the ray?
                            const rt::mesh& g = m.geometry;
                            auto corner = [&](unsigned tri, int c) { return g.positions[g.triangles[tri][std::size_t(c)]]; };
                            const vec3 a = corner(set.source[k], 0);
                            const vec3 n = glm::normalize(glm::cross(corner(set.source[k], 1) - a, corner(set.source[k], 2) - a));
                            real off_plane = 0;
                            for (int c = 0; c < 3; ++c)
                                off_plane = std::max(off_plane, std::fabs(glm::dot(n, corner(triangle, c) - a)));
                            if (off_plane <= real(1e-5) * radius) {
                                ++embree_coplanar;
                                continue;
                            }
                            // a real occluder? Moller-Trumbore in long double on the same inputs
                            if (truly_hits(set.rays[k], corner(triangle, 0), corner(triangle, 1), corner(triangle, 2),
                                           set.tmax[k])) {
                                ++real_occluder;
                                if (examples.size() < 5)
                                    examples.push_back(std::to_string(
                                        t * float(glm::length(set.rays[k].direction)) / float(radius)));
                            }
                        }
                    if (embree_only + rt_only > 0) {
                        std::string others;
                        for (const std::string& e : examples)
                            others += (others.empty() ? "" : " ") + e;
                        const std::string text =
                            std::to_string(rt_only) + " blocked for rt only, " + std::to_string(embree_only) +
                            " for Embree only: " + std::to_string(embree_self) + " by the triangle the ray starts on, " +
                            std::to_string(embree_coplanar) + " by a triangle in its plane (overlapping geometry), " +
                            std::to_string(real_occluder) +
                            " by a triangle the ray truly hits (long-double Moller-Trumbore)" +
                            (others.empty() ? "" : " at distance / scene radius = " + others + " ...");
                        std::cout << "  shadow mismatches: " << text << '\n';
                        rays.note(file + " shadow mismatches (" + std::to_string(threads) + " threads)", text);
                    }
                    const double n = double(set.rays.size());
                    const double rt_mrays = n / rt_seconds / 1e6, embree_mrays = n / embree_seconds / 1e6;
                    rays.row() << file << triangles << set.name << set.rays.size() << threads << rt_seconds
                               << embree_seconds << rt_mrays << embree_mrays << rt_mrays / embree_mrays
                               << (rt_answer.empty() ? std::string("nan") : std::to_string(count_hits(rt_answer)))
                               << count_hits(embree_answer) << hit_mismatch << depth_mismatch;
                    std::cout << "  " << set.name << ", " << threads << " thread(s): rt " << rt_mrays
                              << " Mrays/s, Embree " << embree_mrays << " Mrays/s, ratio " << rt_mrays / embree_mrays
                              << "; hits " << (rt_answer.empty() ? 0 : count_hits(rt_answer)) << " vs "
                              << count_hits(embree_answer) << ", mismatches " << hit_mismatch << " + "
                              << depth_mismatch << " in depth\n";
                }
            }
        }
        rays.write(o, "embree_rays.csv");
        builds.write(o, "embree_build.csv");
        return 0;
    });
}
