// Experiment 2: sphere intersection, rays per second against error.
//
// A unit sphere (R = 1) at distance D = 1e1 ... 1e6 from a camera at the
// origin; rays from the origin towards random points of a disc of radius 1.2 R
// around the centre, perpendicular to the view (so about 1/1.44 = 69% hit).
// For each D and method (the stage-03 textbook quadratic, hit_sphere_textbook,
// and the library's stable method, hit_sphere) we time the calls and compare
// every answer with a reference computed from the same inputs in long double:
//   - misclassified: the method says hit where the reference misses, or the
//     other way round;
//   - depth error |t - t_ref| / R over the rays both call a hit (median, 99th
//     percentile, maximum).
// This program measures rt::real as it was compiled: bench_sphere is float,
// bench_sphere_double the same source with rt::real = double (CMakeLists.txt).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <rt/core/random.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/intersection/sphere_stable.hpp>

#include "bench.hpp"

namespace {

using rt::real;
using rt::vec3;
using wide = long double;

struct reference_hit {
    bool hit = false;
    wide t = 0;
};

/// The nearest root t >= 0 in long double, from the same (rounded) inputs the
/// methods see, by the stable formulas of Ray Tracing Gems ch. 7 (the
/// discriminant from the perpendicular distance, the roots from q and c/q).
/// Its own error (about 1e-19 relative) is far below float's and double's.
reference_hit reference(const rt::sphere& s, const rt::ray& r)
{
    const wide fx = wide(r.origin.x) - s.center.x, fy = wide(r.origin.y) - s.center.y,
               fz = wide(r.origin.z) - s.center.z;
    const wide dx = r.direction.x, dy = r.direction.y, dz = r.direction.z;
    const wide a = dx * dx + dy * dy + dz * dz;
    const wide b = fx * dx + fy * dy + fz * dz;
    const wide length = std::sqrt(a);
    const wide along = b / length;  // f . d^
    const wide px = fx - along * dx / length, py = fy - along * dy / length, pz = fz - along * dz / length;
    const wide R = s.radius;
    const wide discriminant = a * (R * R - (px * px + py * py + pz * pz));
    reference_hit out;
    if (discriminant < 0)
        return out;
    const wide q = -(b + std::copysign(std::sqrt(discriminant), b));
    const wide c = fx * fx + fy * fy + fz * fz - R * R;
    wide t0 = c / q, t1 = q / a;
    if (t0 > t1)
        std::swap(t0, t1);
    if (t0 >= 0) {
        out.hit = true;
        out.t = t0;
    } else if (t1 >= 0) {
        out.hit = true;
        out.t = t1;
    }
    return out;
}

struct method {
    const char* name;
    bool (*hit)(const rt::sphere&, const rt::ray&, real, real, rt::hit_record&);
};

double percentile(std::vector<double> values, double p)
{
    if (values.empty())
        return 0;
    const std::size_t k = std::min(values.size() - 1, std::size_t(p * double(values.size() - 1) + 0.5));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return values[k];
}

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_sphere", [&] {
        const bench::options o = bench::parse_options(argc, argv, "bench_sphere[_double]: experiment 2, sphere intersection");
        const std::size_t count = o.quick ? 4096 : std::size_t(1) << 20;
        const int repeats = o.quick ? 2 : 7;
        const char* precision = sizeof(real) == 4 ? "float" : "double";
        const method methods[] = {{"textbook", &rt::hit_sphere_textbook}, {"stable", &rt::hit_sphere}};

        bench::csv table("sphere intersection: rays/s against error, textbook vs stable (bench/sphere.cpp)",
                         {"precision", "method", "distance", "rays", "seconds", "mrays_per_s", "ns_per_ray",
                          "reference_hits", "method_hits", "misclassified_fraction", "depth_error_median",
                          "depth_error_p99", "depth_error_max"});
        table.note("scene", "unit sphere at distance D from the eye, rays at a disc of radius 1.2 around its centre");
        table.note("error", "misclassified = hit/miss differs from a long-double reference on the same inputs; "
                            "depth errors |t - t_ref| / R over rays both call a hit");

        for (int exponent = 1; exponent <= 6; ++exponent) {
            const double D = std::pow(10.0, exponent);
            rt::sphere s;
            const vec3 toward = glm::normalize(vec3(real(0.3), real(0.2), real(-1)));
            s.center = real(D) * toward;
            s.radius = 1;
            // an orthonormal pair across the view, for the target disc
            const vec3 across_u = glm::normalize(glm::cross(toward, vec3(0, 1, 0)));
            const vec3 across_v = glm::cross(across_u, toward);
            rt::pcg32 rng(std::uint64_t(exponent), 7);
            std::vector<rt::ray> rays(count);
            for (rt::ray& r : rays) {
                real x, y;
                do { // a uniform point in the unit disc, by rejection
                    x = real(2 * rng.next_float() - 1);
                    y = real(2 * rng.next_float() - 1);
                } while (x * x + y * y > 1);
                const vec3 target = s.center + real(1.2) * (x * across_u + y * across_v);
                r.origin = vec3(0);
                r.direction = glm::normalize(target - r.origin);
            }
            std::vector<reference_hit> expected(count);
            std::size_t reference_hits = 0;
            for (std::size_t k = 0; k < count; ++k) {
                expected[k] = reference(s, rays[k]);
                reference_hits += expected[k].hit;
            }

            for (const method& m : methods) {
                std::vector<rt::hit_record> records(count);
                std::vector<char> hit(count);
                const double seconds = bench::best_time(repeats, [&] {
                    for (std::size_t k = 0; k < count; ++k)
                        hit[k] = m.hit(s, rays[k], real(0), std::numeric_limits<real>::infinity(), records[k]);
                    bench::keep(records);
                });
                std::size_t hits = 0, misclassified = 0;
                std::vector<double> depth_errors;
                for (std::size_t k = 0; k < count; ++k) {
                    hits += hit[k] != 0;
                    if ((hit[k] != 0) != expected[k].hit)
                        ++misclassified;
                    else if (hit[k])
                        depth_errors.push_back(double(std::fabs(wide(records[k].t) - expected[k].t) / s.radius));
                }
                const double max_error =
                    depth_errors.empty() ? 0 : *std::max_element(depth_errors.begin(), depth_errors.end());
                table.row() << precision << m.name << D << count << seconds << double(count) / seconds / 1e6
                            << seconds / double(count) * 1e9 << reference_hits << hits
                            << double(misclassified) / double(count) << percentile(depth_errors, 0.5)
                            << percentile(depth_errors, 0.99) << max_error;
                std::cout << precision << ' ' << m.name << " D=" << D << ": "
                          << double(count) / seconds / 1e6 << " Mrays/s, misclassified "
                          << double(misclassified) / double(count) << ", median depth error "
                          << percentile(depth_errors, 0.5) << " R\n";
            }
        }
        table.write(o, std::string("sphere_") + precision + ".csv");
        return 0;
    });
}
