// Experiment 7: whole frames with shading, shadows and one mirror bounce.
//
// The showcase scene (scenes/showcase.scene, as it is: several lights,
// mirrors, max_depth from the file) and each mesh of ../shared/meshes in a
// scene made here: the mesh in a grey material with a highlight and a weak
// mirror (km 0.25, max_depth 1: one bounce), a point light and a directional
// light; the camera outside the model for the bunnies and the Cornell box,
// at the centre of the box for the architectural scenes. One sample per pixel
// (the center sampler), rendered with rt::render and rt::ray_color over
// rt::accelerator (automatic) on 1 thread and on every hardware thread.
// The rays by kind (camera, shadow, reflection) are counted in a separate
// single-thread pass through a counting wrapper, so the timed renders carry
// no instrumentation.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <rt/accelerator.hpp>
#include <rt/camera.hpp>
#include <rt/obj_loader.hpp>
#include <rt/raytracer.hpp>
#include <rt/renderer.hpp>
#include <rt/scene_loader.hpp>

#include "bench.hpp"

namespace {

using rt::real;
using rt::vec3;

/// An accelerator that counts its queries (single-threaded use only).
struct counting_accelerator {
    const rt::accelerator* inner;
    mutable std::uint64_t closest = 0, any = 0;

    bool closest_hit(const rt::ray& r, real tmin, real tmax, rt::hit_record& rec) const
    {
        ++closest;
        return inner->closest_hit(r, tmin, tmax, rec);
    }
    bool any_hit(const rt::ray& r, real tmin, real tmax) const
    {
        ++any;
        return inner->any_hit(r, tmin, tmax);
    }
};

rt::scene mesh_scene(rt::mesh geometry, bool inside, int width, int height)
{
    rt::scene s;
    s.width = width;
    s.height = height;
    rt::material m;
    m.name = "grey";
    m.ka = m.kd = rt::color(0.7f);
    m.ks = rt::color(0.3f);
    m.p = 32;
    m.km = rt::color(0.25f);
    s.materials.push_back(m);
    geometry.material = 0;
    geometry.face_materials.clear();
    const rt::aabb box = rt::bounds(geometry);
    const vec3 centre = box.center();
    const real radius = real(0.5) * glm::length(box.extent());
    s.shapes.emplace_back(std::move(geometry));
    if (inside) {
        s.cam.eye = centre;
        s.cam.look_at = centre + vec3(1, real(-0.1), real(0.2));
        s.cam.fov_degrees = 90;
    } else {
        s.cam.eye = centre + real(2.2) * radius * glm::normalize(vec3(0.35, 0.3, 1));
        s.cam.look_at = centre;
        s.cam.fov_degrees = 45;
    }
    rt::light point;
    point.kind = rt::light_kind::point;
    point.position = inside ? centre + vec3(real(0.1), real(0.35), real(0.05)) * box.extent()
                            : centre + real(1.5) * radius * glm::normalize(vec3(-0.4, 1, 0.6));
    point.intensity = rt::color(0.8f);
    rt::light sun;
    sun.kind = rt::light_kind::directional;
    sun.direction = vec3(real(-0.3), -1, real(-0.5));
    sun.intensity = rt::color(0.3f);
    s.lights = {point, sun};
    s.max_depth = 1;
    s.background = rt::color(0.5f, 0.6f, 0.8f);
    return s;
}

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_frame", [&] {
        const bench::options o = bench::parse_options(argc, argv, "bench_frame: experiment 7, whole frames");
        const int width = o.quick ? 64 : 640, height = o.quick ? 48 : 480;
        const int repeats = o.quick ? 1 : 3;
        const unsigned all = bench::hardware_threads();

        struct entry {
            std::string name;
            std::unique_ptr<rt::scene> s;
        };
        std::vector<entry> scenes;
        {
            auto showcase = std::make_unique<rt::scene>(
                rt::load_scene(std::filesystem::path(RT_BENCH_SOURCE_DIR) / "scenes/showcase.scene"));
            scenes.push_back({"showcase.scene", std::move(showcase)});
        }
        std::vector<std::string> files = {"stanford-bunny.obj", "bunny-loop2.obj", "conference.obj",
                                          "sibenik.obj",        "sponza-dabrovic.obj", "CornellBox-Original.obj"};
        if (o.quick)
            files = {"stanford-bunny.obj", "CornellBox-Original.obj"};
        for (const std::string& file : files) {
            const std::filesystem::path path = o.shared / "meshes" / file;
            if (!std::filesystem::exists(path)) {
                std::cout << "skipping " << path.string() << ": not found\n";
                continue;
            }
            const bool inside = file == "conference.obj" || file == "sibenik.obj" || file == "sponza-dabrovic.obj";
            scenes.push_back({file, std::make_unique<rt::scene>(
                                        mesh_scene(rt::load_obj(path).geometry, inside, width, height))});
        }

        bench::csv table("whole frame: shading, shadows, one mirror bounce (bench/frame.cpp)",
                         {"scene", "width", "height", "threads", "build_seconds", "seconds", "camera_rays",
                          "shadow_rays", "reflection_rays", "mrays_per_s", "speedup"});
        table.note("render", std::to_string(width) + "x" + std::to_string(height) +
                                 " (the showcase at its own aspect ratio), 1 spp, center sampler, box filter; "
                                 "best of " + std::to_string(repeats));
        for (const entry& e : scenes) {
            const rt::scene& s = *e.s;
            const int w = width, h = e.name == "showcase.scene" ? width * s.height / s.width : height;
            const auto build_start = bench::clock::now();
            const rt::accelerator accel(s, rt::accelerator_kind::automatic);
            const double build = bench::seconds_since(build_start);
            const rt::ray_generator gen = rt::make_ray_generator(s.cam, w, h);
            rt::render_options ro;
            ro.width = w;
            ro.height = h;
            ro.sampler = rt::sampler_kind::center;
            auto ray_at = [&](real x, real y) { return rt::generate_ray(gen, x, y); };

            // the count, one thread, instrumented
            counting_accelerator counter{&accel};
            ro.threads = 1;
            rt::render(ro, ray_at, [&](const rt::ray& r, rt::sample_context&) { return rt::ray_color(s, counter, r); });
            const std::uint64_t camera = std::uint64_t(w) * std::uint64_t(h);
            const std::uint64_t reflection = counter.closest - camera, shadow = counter.any;
            const double total = double(camera + reflection + shadow);

            double one_thread = 0;
            for (unsigned threads : {1u, all}) {
                ro.threads = int(threads);
                const double seconds = bench::best_time(repeats, [&] {
                    rt::render(ro, ray_at,
                               [&](const rt::ray& r, rt::sample_context&) { return rt::ray_color(s, accel, r); });
                });
                if (threads == 1)
                    one_thread = seconds;
                table.row() << e.name << w << h << threads << build << seconds << camera << shadow << reflection
                            << total / seconds / 1e6 << one_thread / seconds;
                std::cout << e.name << ", " << threads << " thread(s): " << seconds << " s, " << total / seconds / 1e6
                          << " Mrays/s (" << camera << " camera, " << shadow << " shadow, " << reflection
                          << " reflection rays), speed-up " << one_thread / seconds << '\n';
                if (all == 1)
                    break;
            }
        }
        table.write(o, "frame.csv");
        return 0;
    });
}
