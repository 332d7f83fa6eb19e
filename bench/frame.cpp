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
//
// With Embree (Debian libembree-dev), a second table is what a user feels:
// for each mesh, the build plus a 1-spp and a 16-spp frame at 1280x720 on
// every hardware thread, by rt (rt::accelerator, its default build) and by
// Embree (rtcIntersect1 / rtcOccluded1, its default build) under the same
// shading: rt::ray_color, given Embree's hits as rt's hit records.
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/camera/camera.hpp>
#include <rt/input/obj_loader.hpp>
#include <rt/shading/raytracer.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/input/scene_loader.hpp>

#include "bench.hpp"
#if defined(RT_BENCH_HAS_EMBREE)
#include <rt/scene/mesh.hpp>
#include <rt/scene/triangle_shape.hpp>

#include "embree_scene.hpp"
#endif

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

#if defined(RT_BENCH_HAS_EMBREE)
/// Embree's hits as rt's hit records, so rt::ray_color shades them as it
/// shades rt's own: the point and its error bound from Embree's t and
/// barycentrics (rt::fill_triangle_record), Embree's geometric normal, and the
/// mesh's shading normal and material (rt::complete_mesh_hit).
struct embree_accelerator {
    const bench::embree_scene* scene;
    const rt::mesh* geometry;

    bool closest_hit(const rt::ray& r, real tmin, real tmax, rt::hit_record& rec) const
    {
        float t = 0, u = 0, v = 0;
        unsigned triangle = 0;
        vec3 normal;
        if (!scene->closest_with_normal(r, float(tmax), t, triangle, normal, u, v, float(tmin)))
            return false;
        const rt::index3& corner = geometry->triangles[triangle];
        rt::triangle_hit h;
        h.t = real(t);
        h.b1 = real(u);
        h.b2 = real(v);
        h.b0 = 1 - h.b1 - h.b2;
        rt::fill_triangle_record(geometry->positions[corner[0]], geometry->positions[corner[1]],
                                 geometry->positions[corner[2]], normal, r, h, rec);
        rt::complete_mesh_hit(*geometry, triangle, rec);
        rec.shape = 0;
        return true;
    }
    bool any_hit(const rt::ray& r, real tmin, real tmax) const
    {
        return scene->occluded(r, float(tmin), float(tmax));
    }
};

/// The mean over channels of |a - b|.
double mean_difference(const rt::image& a, const rt::image& b)
{
    double sum = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const rt::color d = glm::abs(a.at(x, y) - b.at(x, y));
            sum += double(d.r) + double(d.g) + double(d.b);
        }
    return sum / (3.0 * double(a.width) * double(a.height));
}
#endif

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

struct entry {
    std::string name;
    std::unique_ptr<rt::scene> s;
    rt::mesh geometry;  ///< a copy of a mesh scene's one shape, for Embree
};

#if defined(RT_BENCH_HAS_EMBREE)
/// What a user feels: build + frame at 1280x720, 1 and 16 spp, every
/// hardware thread, rt against Embree under the same shading. The engines
/// alternate (rt, Embree, rt, ...) so both see the same machine.
void frame_against_embree(const bench::options& o, const std::vector<entry>& scenes)
{
    const int width = o.quick ? 64 : 1280, height = o.quick ? 36 : 720;
    const int repeats = o.quick ? 1 : 3;
    bench::csv table("whole frame, build included: rt against Embree " RTC_VERSION_STRING " (bench/frame.cpp)",
                     {"scene", "width", "height", "spp", "threads", "rt_build_seconds", "rt_frame_seconds",
                      "embree_build_seconds", "embree_frame_seconds", "ratio_rt_over_embree",
                      "mean_difference", "rt_plain_build_seconds", "rt_plain_frame_seconds"});
    table.note("render", std::to_string(width) + "x" + std::to_string(height) +
                             ", jittered sampler, box filter, every hardware thread; each engine's default "
                             "build (rt: spatial splits; Embree: medium quality), and rt without spatial "
                             "splits (plain); best of " +
                             std::to_string(repeats));
    for (const entry& e : scenes) {
        if (e.geometry.triangles.empty())
            continue;  // the showcase: spheres and several shapes, not one mesh
        rt::scene s = *e.s;
        s.width = width;
        s.height = height;
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, width, height);
        auto ray_at = [&](real x, real y) { return rt::generate_ray(gen, x, y); };
        for (int spp : {1, 16}) {
            rt::render_options ro;
            ro.width = width;
            ro.height = height;
            ro.samples_per_pixel = o.quick ? std::min(spp, 2) : spp;
            double rt_build = 1e300, rt_frame = 1e300, embree_build = 1e300, embree_frame = 1e300;
            double plain_build = 1e300, plain_frame = 1e300;
            rt::image rt_image, embree_image;
            const auto rt_run = [&](const rt::bvh_options& options, double& build, double& frame) {
                const auto start = bench::clock::now();
                const rt::accelerator accel(s, rt::accelerator_kind::automatic, options);
                build = std::min(build, bench::seconds_since(start));
                const auto frame_start = bench::clock::now();
                rt_image = rt::render(ro, ray_at, [&](const rt::ray& r, rt::sample_context&) {
                               return rt::ray_color(s, accel, r);
                           }).pixels;
                frame = std::min(frame, bench::seconds_since(frame_start));
            };
            rt::bvh_options plain;
            plain.spatial_budget = 0;
            for (int k = 0; k < repeats; ++k) {
                rt_run(plain, plain_build, plain_frame);
                rt_run(rt::bvh_options{}, rt_build, rt_frame);
                {
                    const bench::embree_scene embree(e.geometry, nullptr);
                    embree_build = std::min(embree_build, embree.build_seconds());
                    const embree_accelerator accel{&embree, &e.geometry};
                    const auto frame_start = bench::clock::now();
                    embree_image = rt::render(ro, ray_at, [&](const rt::ray& r, rt::sample_context&) {
                                       return rt::ray_color(s, accel, r);
                                   }).pixels;
                    embree_frame = std::min(embree_frame, bench::seconds_since(frame_start));
                }
            }
            const double ratio = (rt_build + rt_frame) / (embree_build + embree_frame);
            const double difference = mean_difference(rt_image, embree_image);
            table.row() << e.name << width << height << ro.samples_per_pixel << bench::hardware_threads()
                        << rt_build << rt_frame << embree_build << embree_frame << ratio << difference
                        << plain_build << plain_frame;
            std::cout << e.name << ", " << ro.samples_per_pixel << " spp at " << width << "x" << height
                      << ": rt " << rt_build << " + " << rt_frame << " s, Embree " << embree_build << " + "
                      << embree_frame << " s, rt/Embree " << ratio << ", mean difference " << difference
                      << "; rt without spatial splits " << plain_build << " + " << plain_frame << " s\n";
        }
    }
    table.write(o, "frame_embree.csv");
}
#endif

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_frame", [&] {
        const bench::options o = bench::parse_options(argc, argv, "bench_frame: experiment 7, whole frames");
        const int width = o.quick ? 64 : 640, height = o.quick ? 48 : 480;
        const int repeats = o.quick ? 1 : 3;
        const unsigned all = bench::hardware_threads();

        std::vector<entry> scenes;
        {
            auto showcase = std::make_unique<rt::scene>(
                rt::load_scene(std::filesystem::path(RT_BENCH_SOURCE_DIR) / "scenes/showcase.scene"));
            scenes.push_back({"showcase.scene", std::move(showcase), {}});
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
            auto scene = std::make_unique<rt::scene>(mesh_scene(rt::load_obj(path).geometry, inside, width, height));
            rt::mesh geometry = std::get<rt::mesh>(scene->shapes.front());  // in the scene's grey material
            scenes.push_back({file, std::move(scene), std::move(geometry)});
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
#if defined(RT_BENCH_HAS_EMBREE)
        frame_against_embree(o, scenes);
#endif
        return 0;
    });
}
