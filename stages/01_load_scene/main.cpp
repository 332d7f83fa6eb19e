// Stage 01 - load a scene and print what a student needs to check it: the
// camera statement as loaded (projection, eye, look-at, up, field of view or
// window, focal distance), the counts of shapes, materials and lights, and the
// scene bounds. It runs stage 01's code and nothing later: the camera frame
// u, v, w is stage 02's (stage02_generate_rays prints it).
//
//     stage01_load_scene scenes/showcase.scene
#include <cstdio>
#include <iostream>
#include <variant>

#include <rt/scene/camera_model.hpp>
#include <rt/scene/scene.hpp>

#include "stage_main.hpp"
#include "support.hpp"

namespace {

void print_vector(const char* name, const rt::vec3& v)
{
    std::printf("  %-8s %12.6g %12.6g %12.6g\n", name, double(v.x), double(v.y), double(v.z));
}

const char* usage = "usage: stage01_load_scene SCENE\n"
                    "Loads SCENE and prints its camera as loaded, the counts of shapes, materials and\n"
                    "lights, and the scene bounds (stage 01's code only).\n";

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage01_load_scene", [&] {
        stage::arguments args(argc, argv);
        const std::optional<std::string> scene_file =
            stage::read_command_line(args, usage, "", [](const std::string&) { return false; });
        if (!scene_file)
            return 0; // --help
        const std::string& path = *scene_file;

        rt::check_readable(stage::file_argument(path), "a scene file"); // the reason (errno) when it cannot be read
        const rt::scene s = stage::load_scene(path);
        std::printf("scene %s\n", path.c_str());
        std::printf("image %d x %d, %d sample(s) per pixel, max depth %d\n", s.width, s.height, s.samples, s.max_depth);
        const rt::camera& cam = s.cam;
        std::printf("camera %s\n", rt::name_of(cam.kind));
        print_vector("eye", cam.eye);
        print_vector("look_at", cam.look_at);
        print_vector("up", cam.up);
        if (cam.plane)
            std::printf("  window   l %g r %g b %g t %g (as given)\n", double(cam.plane->l), double(cam.plane->r),
                        double(cam.plane->b), double(cam.plane->t));
        else if (cam.fov_degrees)
            std::printf("  fov      %g degrees (vertical)\n", double(*cam.fov_degrees));
        else
            std::printf("  fov      none given: %s\n", cam.kind == rt::projection::perspective
                                                         ? "45 degrees (the default)"
                                                         : "the window [-1, 1] in v, widened to the aspect (the default)");
        std::printf("  focal    %g\n", double(cam.focal_distance));

        const stage::shape_counts n = stage::count_shapes(s);
        std::printf("shapes %zu: %zu sphere(s), %zu triangle(s), %zu mesh(es) with %zu triangle(s)\n", s.shapes.size(),
                    n.spheres, n.triangles, n.meshes, n.mesh_triangles);
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
