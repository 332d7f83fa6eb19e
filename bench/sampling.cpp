// Experiment 1: sampling, RMSE against a converged reference vs render time.
//
// For each sampler (center, grid, random, jittered, halton) x reconstruction
// filter (box, tent, gaussian, mitchell) x samples per pixel (1, 4, 16, 64,
// 256) we render with rt::render on one thread, time it, and compare the
// image with a reference rendered with the same filter and many more samples
// (jittered, another seed): RMSE over every pixel and channel, values clamped
// to [0, 1] (what a display shows). The slope of log RMSE against log spp is
// fitted by least squares over spp >= 4 and compared with theory for pixels
// crossed by edges: random sampling converges as N^-1/2 (the Monte Carlo
// rate), jittered (stratified) sampling as N^-3/4 (D. P. Mitchell,
// "Consequences of Stratified Sampling in Graphics", SIGGRAPH 1996, abstract:
// the variance of a stratified estimate of a pixel crossed by an edge falls as
// N^-3/2).
//
// One more curve, box filter only: "student", the stage-02 exercises
// (rt::jittered_samples with n x n = spp samples per pixel, rt::box_reconstruct;
// include/rt/camera/pixel_sampling.hpp), in a plain loop over the pixels on one
// thread. It estimates what the library's jittered sampler with the box filter
// estimates, so its curve should lie on that one, slope -3/4. (Benchmarks are
// built from the reference solution only; a student kit has none.)
//
// Scenes (bench_sampling NAME... runs only those named):
//   edges     an analytic pattern seen by an orthographic camera: a checkerboard
//             rotated by 20 degrees and a disc, every pixel's value a step
//             function; nothing but edges and flat areas.
//   showcase  scenes/showcase.scene with shading, shadows and mirrors
//             (rt::ray_color over rt::accelerator), when stage 04 is present.
//   soft      scenes/soft.scene (stage 10: area lights, glossy mirrors, a thin
//             lens) through rt::make_radiance, box filter only: each sample
//             draws its own random lens point, light points and glossy
//             directions, unstratified, so the pixel sampler stratifies only
//             the film. Theory: N^-1/2 for every sampler (the noise of the
//             light, lens and gloss samples dominates once edges are resolved).
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <rt/camera/camera.hpp>
#include <rt/core/error.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/camera/pixel_sampling.hpp>
#include <rt/core/random.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/sampler.hpp>
#if defined(RT_BENCH_HAS_ACCELERATOR)
#include <rt/bvh/accelerator.hpp>
#include <rt/rendering/radiance.hpp>
#include <rt/shading/raytracer.hpp>
#include <rt/input/scene_loader.hpp>
#endif

#include "bench.hpp"

namespace {

using rt::real;
using rt::vec3;

/// The edge-heavy pattern at the point (x, y) of the plane z = 0.
rt::color edge_pattern(real x, real y)
{
    // the disc: centre (0.3, -0.2), radius 0.35
    const real dx = x - real(0.3), dy = y + real(0.2);
    if (dx * dx + dy * dy < real(0.35 * 0.35))
        return rt::color(0.95f, 0.75f, 0.2f);
    // a checkerboard of 0.23-wide squares, rotated by 20 degrees
    const real c = real(0.9396926207859084), s = real(0.3420201433256687);
    const real u = (c * x + s * y) / real(0.23), v = (-s * x + c * y) / real(0.23);
    const bool odd = (int(std::floor(u)) + int(std::floor(v))) % 2 != 0;
    return odd ? rt::color(0.9f) : rt::color(0.05f, 0.1f, 0.2f);
}

struct scene_case {
    std::string name;
    int width = 0, height = 0;
    std::function<rt::ray(real, real)> ray_at;
    std::function<rt::color(const rt::ray&, rt::sample_context&)> radiance;
    bool box_only = false;  ///< render with the box filter alone (a costly scene)
    const char* theory_random = "-0.5", *theory_jittered = "-0.75";
};

double rmse(const rt::image& a, const rt::image& b)
{
    double sum = 0;
    for (std::size_t k = 0; k < a.pixels.size(); ++k)
        for (int c = 0; c < 3; ++c) {
            const double x = std::min(1.0, std::max(0.0, double(a.pixels[k][c])));
            const double y = std::min(1.0, std::max(0.0, double(b.pixels[k][c])));
            sum += (x - y) * (x - y);
        }
    return std::sqrt(sum / double(3 * a.pixels.size()));
}

/// Least-squares slope of log y against log x.
double log_slope(const std::vector<double>& x, const std::vector<double>& y)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double lx = std::log(x[k]), ly = std::log(y[k]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double d = n * sxx - sx * sx;
    return d != 0 ? (n * sxy - sx * sy) / d : 0;
}

rt::render_result render_case(const scene_case& sc, rt::sampler_kind sampler, rt::filter_kind filter, int spp,
                               int threads, std::uint64_t seed)
{
    rt::render_options o;
    o.width = sc.width;
    o.height = sc.height;
    o.samples_per_pixel = spp;
    o.sampler = sampler;
    o.reconstruction = rt::make_filter(filter);
    o.threads = threads;
    o.seed = seed;
    return rt::render(o, [&](real x, real y) { return sc.ray_at(x, y); },
                      [&](const rt::ray& r, rt::sample_context& ctx) { return sc.radiance(r, ctx); });
}

/// The stage-02 exercises as a renderer: n x n jittered samples per pixel, the box.
rt::image render_student(const scene_case& sc, int n, std::uint64_t seed)
{
    rt::image img(sc.width, sc.height);
    std::vector<rt::color> values;
    for (int j = 0; j < sc.height; ++j)
        for (int i = 0; i < sc.width; ++i) {
            const std::uint64_t pixel_index = std::uint64_t(j) * std::uint64_t(sc.width) + std::uint64_t(i);
            rt::pcg32 rng = rt::seeded_generator(seed, pixel_index, 0, rt::sampler_stream);
            const std::vector<rt::vec2> positions = rt::jittered_samples(i, j, n, rng);
            values.clear();
            for (std::size_t k = 0; k < positions.size(); ++k) {
                rt::sample_context ctx;
                ctx.rng = rt::seeded_generator(seed, pixel_index, k + 1, rt::integrator_stream);
                values.push_back(sc.radiance(sc.ray_at(positions[k].x, positions[k].y), ctx));
            }
            img.at(i, sc.height - 1 - j) = rt::box_reconstruct(i, j, positions, values); // top row first
        }
    return img;
}

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_sampling", [&] {
        const bench::options o = bench::parse_options(argc, argv, "bench_sampling: experiment 1, sampling error against time");
        const int repeats = o.quick ? 1 : 2;
        const std::vector<int> spps = o.quick ? std::vector<int>{1, 4, 16} : std::vector<int>{1, 4, 16, 64, 256};

        std::vector<scene_case> cases;
        std::vector<int> reference_spps;
        {
            scene_case edges;
            edges.name = "edges";
            edges.width = edges.height = o.quick ? 32 : 128;
            rt::camera cam;
            cam.kind = rt::projection::orthographic;
            cam.eye = vec3(0, 0, 1);
            cam.look_at = vec3(0);
            const rt::ray_generator gen = rt::make_ray_generator(cam, edges.width, edges.height);
            edges.ray_at = [gen](real x, real y) { return rt::generate_ray(gen, x, y); };
            edges.radiance = [](const rt::ray& r, rt::sample_context&) { return edge_pattern(r.origin.x, r.origin.y); };
            cases.push_back(edges);
            reference_spps.push_back(o.quick ? 1024 : 16384);
        }
#if defined(RT_BENCH_HAS_ACCELERATOR)
        auto showcase_scene =
            std::make_shared<rt::scene>(rt::load_scene(std::filesystem::path(RT_BENCH_SOURCE_DIR) / "scenes/showcase.scene"));
        auto showcase_accel = std::make_shared<rt::accelerator>(*showcase_scene, rt::accelerator_kind::automatic);
        {
            scene_case showcase;
            showcase.name = "showcase";
            showcase.width = o.quick ? 32 : 160;
            showcase.height = o.quick ? 18 : 90;
            const rt::ray_generator gen = rt::make_ray_generator(showcase_scene->cam, showcase.width, showcase.height);
            showcase.ray_at = [gen](real x, real y) { return rt::generate_ray(gen, x, y); };
            showcase.radiance = [showcase_scene, showcase_accel](const rt::ray& r, rt::sample_context&) {
                return rt::ray_color(*showcase_scene, *showcase_accel, r);
            };
            cases.push_back(showcase);
            reference_spps.push_back(o.quick ? 256 : 4096);
        }
        auto soft_scene =
            std::make_shared<rt::scene>(rt::load_scene(std::filesystem::path(RT_BENCH_SOURCE_DIR) / "scenes/soft.scene"));
        {
            scene_case soft;
            soft.name = "soft";
            soft.width = o.quick ? 32 : 160;
            soft.height = o.quick ? 18 : 90;
            soft.box_only = true;
            soft.theory_jittered = "-0.5";
            const rt::ray_generator gen = rt::make_ray_generator(soft_scene->cam, soft.width, soft.height);
            soft.ray_at = [gen](real x, real y) { return rt::generate_ray(gen, x, y); };
            // the shaded color with this sample's random numbers (lens, light points, gloss)
            const rt::radiance_function shaded = rt::make_radiance(*soft_scene, rt::aov_kind::shaded);
            soft.radiance = [soft_scene, shaded](const rt::ray& r, rt::sample_context& ctx) { return shaded(r, ctx); };
            cases.push_back(soft);
            reference_spps.push_back(o.quick ? 256 : 4096);
        }
#endif
        // bench_sampling [SCENE...]: only the scenes named (edges, showcase, soft)
        if (!o.extra.empty()) {
            std::vector<scene_case> chosen;
            std::vector<int> chosen_spps;
            for (const std::string& name : o.extra) {
                std::size_t k = 0;
                while (k < cases.size() && cases[k].name != name)
                    ++k;
                if (k == cases.size())
                    throw rt::error("expected a scene name (edges, showcase or soft), found '" + name + "'");
                chosen.push_back(cases[k]);
                chosen_spps.push_back(reference_spps[k]);
            }
            cases = chosen;
            reference_spps = chosen_spps;
        }
        const rt::sampler_kind samplers[] = {rt::sampler_kind::center, rt::sampler_kind::grid, rt::sampler_kind::random,
                                             rt::sampler_kind::jittered, rt::sampler_kind::halton};
        const rt::filter_kind filters[] = {rt::filter_kind::box, rt::filter_kind::tent, rt::filter_kind::gaussian,
                                           rt::filter_kind::mitchell};

        bench::csv table("sampling: RMSE against a converged reference of the same filter vs render time "
                         "(bench/sampling.cpp)",
                         {"scene", "width", "height", "sampler", "filter", "spp", "effective_spp", "seconds", "rmse",
                          "reference_spp"});
        bench::csv slopes("sampling: fitted slopes of log RMSE against log spp, spp >= 4 (bench/sampling.cpp)",
                          {"scene", "sampler", "filter", "slope", "theory"});
        for (bench::csv* t : {&table, &slopes}) {
            t->note("render", "rt::render on 1 thread, best of " + std::to_string(repeats) +
                                  "; reference: jittered, seed 99, all threads");
            t->note("rmse", "over every pixel and channel, values clamped to [0, 1]");
        }

        for (std::size_t c = 0; c < cases.size(); ++c) {
            const scene_case& sc = cases[c];
            for (const rt::filter_kind filter : filters) {
                if (sc.box_only && filter != rt::filter_kind::box)
                    continue;
                const auto start = bench::clock::now();
                const rt::image reference =
                    render_case(sc, rt::sampler_kind::jittered, filter, reference_spps[c], 0, 99).pixels;
                std::cout << sc.name << ' ' << rt::name_of(filter) << ": reference " << reference_spps[c]
                          << " spp in " << bench::seconds_since(start) << " s\n";
                for (const rt::sampler_kind sampler : samplers) {
                    std::vector<double> xs, ys;
                    for (const int spp : spps) {
                        if (sampler == rt::sampler_kind::center && spp > 1)
                            break; // one sample whatever is asked
                        rt::render_result result;
                        const double seconds =
                            bench::best_time(repeats, [&] { result = render_case(sc, sampler, filter, spp, 1, 1); });
                        const double error = rmse(result.pixels, reference);
                        table.row() << sc.name << sc.width << sc.height << rt::name_of(sampler) << rt::name_of(filter)
                                    << spp << result.stats.samples_per_pixel << seconds << error << reference_spps[c];
                        if (spp >= 4) {
                            xs.push_back(double(result.stats.samples_per_pixel));
                            ys.push_back(error);
                        }
                    }
                    if (xs.size() >= 2) {
                        const char* theory = sampler == rt::sampler_kind::random     ? sc.theory_random
                                             : sampler == rt::sampler_kind::jittered ? sc.theory_jittered
                                                                                     : "";
                        const double slope = log_slope(xs, ys);
                        slopes.row() << sc.name << rt::name_of(sampler) << rt::name_of(filter) << slope << theory;
                        std::cout << "  " << rt::name_of(sampler) << ": slope " << slope << '\n';
                    }
                }
                if (filter == rt::filter_kind::box) { // the student's sampler and box (stage 02)
                    std::vector<double> xs, ys;
                    for (const int spp : spps) {
                        int n = 1;
                        while (n * n < spp)
                            ++n;
                        rt::image result;
                        const double seconds = bench::best_time(repeats, [&] { result = render_student(sc, n, 1); });
                        const double error = rmse(result, reference);
                        table.row() << sc.name << sc.width << sc.height << "student" << rt::name_of(filter) << spp
                                    << n * n << seconds << error << reference_spps[c];
                        if (spp >= 4) {
                            xs.push_back(double(n * n));
                            ys.push_back(error);
                        }
                    }
                    const double slope = log_slope(xs, ys);
                    slopes.row() << sc.name << "student" << rt::name_of(filter) << slope << sc.theory_jittered;
                    std::cout << "  student (stage 02): slope " << slope << '\n';
                }
            }
        }
        table.write(o, "sampling.csv");
        slopes.write(o, "sampling_slopes.csv");
        return 0;
    });
}
