// Experiment 8: path tracing, noise against time for each way of sampling
// the light (stage 11, include/rt/path_tracing/path_tracer.hpp).
//
// The Cornell box of ../shared (scenes/cornell.scene, its own light only) is
// rendered by rt::render_paths on one thread with each strategy (uniform and
// cosine BSDF sampling, next-event estimation, MIS) at 4, 16, 64 and 256
// samples per pixel, and with adaptive sampling (CS184's rule, batches of 16,
// at most 1024 samples) at the tolerances 0.4, 0.2, 0.1 and 0.05; each image
// is timed and compared with a reference (MIS, 4096 samples, another seed, all
// threads): RMSE over every pixel and channel, values clamped to [0, 1] (what
// a display shows). The reference's own noise (1/64 of one sample's standard
// deviation) adds about 3% to the RMSE at 256 samples and less below.
// Russian roulette from bounce 3 everywhere. Nothing asserts a timing.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/path_tracing/path_tracer.hpp>
#include <rt/rendering/radiance.hpp>
#include <rt/input/scene_loader.hpp>

#include "bench.hpp"

namespace {

double rmse(const rt::image& a, const rt::image& b)
{
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double x = std::clamp(double(a.pixels[i][c]), 0.0, 1.0);
            const double y = std::clamp(double(b.pixels[i][c]), 0.0, 1.0);
            sum += (x - y) * (x - y);
        }
    return std::sqrt(sum / (3.0 * double(a.pixels.size())));
}

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_path", [&] {
        const bench::options o =
            bench::parse_options(argc, argv, "bench_path: experiment 8, path tracing noise against time");
        const std::filesystem::path scene_file = std::filesystem::path(RT_BENCH_SOURCE_DIR) / "scenes" / "cornell.scene";
        if (!std::filesystem::exists(o.shared / "meshes" / "CornellBox-Original.obj")) {
            std::cout << "bench_path: skipped, no " << (o.shared / "meshes" / "CornellBox-Original.obj").string() << '\n';
            return 0;
        }
        rt::scene s = rt::load_scene(scene_file);
        const int size = o.quick ? 24 : 96;
        s.width = s.height = size;
        const rt::accelerator accel(s);
        const rt::emitter_list lights = rt::find_emitters(s);
        const rt::ray_source rays = rt::camera_rays(s.cam, s.width, s.height);
        rt::path_render_options base;
        base.width = base.height = size;
        const int reference_spp = o.quick ? 256 : 4096;
        const std::vector<int> spps = o.quick ? std::vector<int>{4, 16} : std::vector<int>{4, 16, 64, 256};
        const std::vector<double> tolerances = o.quick ? std::vector<double>{0.4, 0.2}
                                                       : std::vector<double>{0.4, 0.2, 0.1, 0.05};

        rt::path_render_options ref = base;
        ref.samples_per_pixel = reference_spp;
        ref.seed = 99;
        ref.threads = 0;
        const auto start = bench::clock::now();
        const rt::image reference = rt::render_paths(s, accel, lights, rays, ref).pixels;
        std::cout << "reference: MIS, " << reference_spp << " spp in " << bench::seconds_since(start) << " s\n";

        bench::csv table("path: RMSE against a converged reference vs render time, Cornell box (bench/path.cpp)",
                         {"strategy", "adaptive", "spp", "tolerance", "mean_spp", "seconds", "rmse"});
        table.note("scene", "scenes/cornell.scene at " + std::to_string(size) + "x" + std::to_string(size) +
                                ", rt::render_paths on 1 thread, Russian roulette from bounce 3");
        table.note("reference", "MIS, " + std::to_string(reference_spp) + " spp, seed 99, all threads");
        table.note("rmse", "over every pixel and channel, values clamped to [0, 1]");
        const int adaptive_max = o.quick ? 64 : 1024;
        table.note("adaptive", "CS184's rule, batches of 16, at most " + std::to_string(adaptive_max) +
                                   " samples per pixel");
        for (const rt::path_strategy kind : {rt::path_strategy::uniform, rt::path_strategy::cosine,
                                             rt::path_strategy::nee, rt::path_strategy::mis}) {
            rt::path_render_options run = base;
            run.threads = 1;
            run.seed = 1;
            run.path.strategy = kind;
            for (const int spp : spps) {
                run.samples_per_pixel = spp;
                const rt::path_render_result r = rt::render_paths(s, accel, lights, rays, run);
                const double error = rmse(r.pixels, reference);
                table.row() << rt::name_of(kind) << "no" << spp << 0 << spp << r.seconds << error;
                std::cout << rt::name_of(kind) << " " << spp << " spp: " << r.seconds << " s, RMSE " << error << '\n';
            }
            if (kind == rt::path_strategy::uniform)
                continue; // its adaptive curve is cosine's, only slower
            run.adaptive = true;
            run.batch = 16;
            run.samples_per_pixel = adaptive_max;
            for (const double tolerance : tolerances) {
                run.max_tolerance = tolerance;
                const rt::path_render_result r = rt::render_paths(s, accel, lights, rays, run);
                double mean = 0;
                for (const int n : r.samples)
                    mean += double(n) / double(r.samples.size());
                const double error = rmse(r.pixels, reference);
                table.row() << rt::name_of(kind) << "yes" << run.samples_per_pixel << tolerance << mean << r.seconds
                            << error;
                std::cout << rt::name_of(kind) << " adaptive " << tolerance << ": " << mean << " spp on average, "
                          << r.seconds << " s, RMSE " << error << '\n';
            }
        }
        table.write(o, "path.csv");
        return 0;
    });
}
