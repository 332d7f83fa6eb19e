// Stage 01 - load a scene and print what a student needs to check it:
// the camera frame e, u, v, w and window, the counts of shapes, materials and
// lights, and the scene bounds.
//
//     stage01_load_scene scenes/showcase.scene
#include <cstdio>
#include <iostream>
#include <variant>

#include <rt/camera.hpp>
#include <rt/scene.hpp>
#include <rt/scene_loader.hpp>

#include "stage_main.hpp"

namespace {

void print_vector(const char* name, const rt::vec3& v)
{
    std::printf("  %-8s %12.6g %12.6g %12.6g\n", name, double(v.x), double(v.y), double(v.z));
}

const char* usage = "usage: stage01_load_scene SCENE\n"
                    "Loads SCENE and prints its camera frame, window, counts and bounds.\n";

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage01_load_scene", [&] {
        stage::arguments args(argc, argv);
        if (args.done())
            throw rt::error("expected a scene file, found no argument; " + std::string("usage: stage01_load_scene SCENE"));
        const std::string path = args.take();
        if (path == "--help" || path == "-h") {
            std::cout << usage;
            return 0;
        }
        if (!args.done())
            throw rt::error("expected one scene file, found also '" + args.peek() + "'; usage: stage01_load_scene SCENE");

        rt::check_readable(path, "a scene file"); // the reason (errno) when it cannot be read
        const rt::scene s = rt::load_scene(path);
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
        std::printf("scene %s\n", path.c_str());
        std::printf("image %d x %d, %d sample(s) per pixel, max depth %d\n", s.width, s.height, s.samples, s.max_depth);
        std::printf("camera %s\n", s.cam.kind == rt::projection::perspective ? "perspective" : "orthographic");
        print_vector("e", gen.e);
        print_vector("u", gen.basis.u);
        print_vector("v", gen.basis.v);
        print_vector("w", gen.basis.w);
        std::printf("  window   l %g r %g b %g t %g, focal distance d %g\n", double(gen.plane.l), double(gen.plane.r),
                    double(gen.plane.b), double(gen.plane.t), double(gen.d));

        std::size_t spheres = 0, triangles = 0, meshes = 0, mesh_triangles = 0;
        for (const rt::shape& item : s.shapes) {
            if (std::holds_alternative<rt::sphere>(item))
                ++spheres;
            else if (std::holds_alternative<rt::triangle>(item))
                ++triangles;
            else {
                ++meshes;
                mesh_triangles += std::get<rt::mesh>(item).triangles.size();
            }
        }
        std::printf("shapes %zu: %zu sphere(s), %zu triangle(s), %zu mesh(es) with %zu triangle(s)\n", s.shapes.size(),
                    spheres, triangles, meshes, mesh_triangles);
        std::printf("materials %zu, lights %zu\n", s.materials.size(), s.lights.size());
        const rt::aabb box = rt::scene_bounds(s);
        if (box.empty()) {
            std::printf("bounds (empty scene)\n");
        } else {
            print_vector("min", box.lo);
            print_vector("max", box.hi);
        }
        return 0;
    });
}
