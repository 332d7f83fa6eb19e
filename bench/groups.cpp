// Experiment 4: groups, nanoseconds per ray against primitive count, flat
// list vs BVH, and the crossover that accelerator_kind::automatic should use.
//
// Scenes of N = 1 ... 1e6 separate shapes (every other one a sphere, the
// others triangles) of random position and orientation in the unit cube, sized
// so that they cover the cube's cross-section about twice whatever N is (a
// shape's linear size ~ N^-1/2). Rays: primary rays of a camera outside the
// cube through random film positions. For each N and accelerator kind we time
// closest_hit on one thread (the flat list gets fewer rays at large N: its
// cost per ray grows as N), and the build. The measured crossover is the N at
// which the two log-log curves cross (linear interpolation of log ns against
// log N between the two counts that bracket it).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/camera/camera.hpp>
#include <rt/core/random.hpp>
#include <rt/scene/scene.hpp>

#include "bench.hpp"

namespace {

using rt::real;
using rt::vec3;

rt::scene random_shapes(std::size_t count, std::uint64_t seed)
{
    rt::scene s;
    rt::pcg32 rng(seed, 3);
    auto uniform = [&] { return real(rng.next_float()); };
    // total cross-section about 2 (twice the cube's face): N pi r^2 = 2
    const real size = std::sqrt(real(2) / (real(3.14159265) * real(count)));
    s.shapes.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
        const vec3 centre{uniform(), uniform(), uniform()};
        if (k % 2 == 0) {
            rt::sphere sp;
            sp.center = centre;
            sp.radius = size;
            s.shapes.emplace_back(sp);
        } else {
            rt::triangle t;
            auto corner = [&] { return centre + real(2) * size * (vec3{uniform(), uniform(), uniform()} - real(0.5)); };
            t.a = corner();
            t.b = corner();
            t.c = corner();
            s.shapes.emplace_back(t);
        }
    }
    return s;
}

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_groups", [&] {
        const bench::options o = bench::parse_options(argc, argv, "bench_groups: experiment 4, flat list vs BVH");
        const int repeats = o.quick ? 1 : 3;
        std::vector<std::size_t> counts;
        const int top = o.quick ? 4 : 6;
        for (const std::size_t small : {1, 2, 3, 5}) // below the 10 of the issue, to find a crossover there
            counts.push_back(small);
        for (int e = 1; e <= top; ++e) {
            counts.push_back(std::size_t(std::pow(10.0, e)));
            if (e < top)
                counts.push_back(std::size_t(std::lround(3 * std::pow(10.0, e))));
        }
        const double budget = o.quick ? 2e6 : 4e8; // ray-shape tests per flat measurement

        bench::csv table("groups: ns per ray against primitive count, flat vs BVH (bench/groups.cpp)",
                         {"primitives", "kind", "rays", "seconds", "ns_per_ray", "build_seconds", "hits"});
        table.note("scene", "N shapes (spheres and triangles alternately) at random in the unit cube, "
                            "covering its cross-section about twice");
        table.note("rays", "primary rays of a camera outside the cube through random film positions; closest hit, 1 thread");

        std::vector<double> flat_ns, bvh_ns;
        for (const std::size_t n : counts) {
            const rt::scene s = random_shapes(n, 42);
            rt::camera cam;
            cam.eye = vec3(real(0.5), real(0.8), real(3.2));
            cam.look_at = vec3(real(0.5));
            cam.fov_degrees = 30;
            const rt::ray_generator gen = rt::make_ray_generator(cam, 512, 512);
            const std::size_t max_rays = o.quick ? 2048 : std::size_t(1) << 17;
            for (const auto kind : {rt::accelerator_kind::flat, rt::accelerator_kind::bvh,
                                    rt::accelerator_kind::automatic}) {
                const char* name = kind == rt::accelerator_kind::flat  ? "flat"
                                   : kind == rt::accelerator_kind::bvh ? "bvh"
                                                                        : "automatic";
                std::size_t ray_count = max_rays;
                if (kind != rt::accelerator_kind::bvh) // the flat list (and automatic, which may be flat)
                    ray_count = std::max<std::size_t>(64, std::min(max_rays, std::size_t(budget / double(n))));
                rt::pcg32 rng(7, 9);
                std::vector<rt::ray> rays(ray_count);
                for (rt::ray& r : rays) {
                    const real x = real(512 * rng.next_float()), y = real(512 * rng.next_float());
                    r = rt::generate_ray(gen, x, y);
                }
                double build = 1e300;
                for (int k = 0; k < repeats; ++k) {
                    const auto start = bench::clock::now();
                    const rt::accelerator probe(s, kind);
                    build = std::min(build, bench::seconds_since(start));
                    bench::keep(probe);
                }
                const rt::accelerator accel(s, kind);
                std::size_t hits = 0;
                const double seconds = bench::best_time(repeats, [&] {
                    hits = 0;
                    for (const rt::ray& r : rays) {
                        rt::hit_record rec;
                        hits += accel.closest_hit(r, real(0), std::numeric_limits<real>::infinity(), rec);
                    }
                });
                const double ns = seconds / double(ray_count) * 1e9;
                table.row() << n << name << ray_count << seconds << ns << build << hits;
                std::cout << n << " shapes, " << name << ": " << ns << " ns/ray, build " << build << " s, "
                          << hits << "/" << ray_count << " hit\n";
                if (kind == rt::accelerator_kind::flat)
                    flat_ns.push_back(ns);
                else if (kind == rt::accelerator_kind::bvh)
                    bvh_ns.push_back(ns);
            }
        }
        // the crossover: the first count at which the BVH is faster, interpolated in log-log
        std::string crossover = "none in range (the BVH is never faster)";
        for (std::size_t k = 0; k < counts.size(); ++k) {
            if (bvh_ns[k] < flat_ns[k]) {
                if (k == 0) {
                    crossover = "below " + std::to_string(counts[0]) + " (the BVH is faster at every count)";
                } else {
                    const double a = std::log(flat_ns[k - 1] / bvh_ns[k - 1]), b = std::log(flat_ns[k] / bvh_ns[k]);
                    const double f = a / (a - b); // where log(flat/bvh) = 0
                    const double x = std::exp(std::log(double(counts[k - 1])) +
                                              f * (std::log(double(counts[k])) - std::log(double(counts[k - 1]))));
                    crossover = std::to_string(std::lround(x)) + " primitives";
                }
                break;
            }
        }
        table.note("measured crossover", crossover);
        const std::string threshold = std::to_string(rt::flat_list_crossover) + " primitives (rt::flat_list_crossover)";
        table.note("automatic threshold", threshold);
        std::cout << "measured crossover: " << crossover << "; automatic uses flat below " << threshold << '\n';
        table.write(o, "groups.csv");
        return 0;
    });
}
