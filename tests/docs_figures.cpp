// docs_figures.cpp - no figure in the docs can go stale (label docs).
//
// A page quotes a number the code produces as
//     <!-- figure: stage03.far_spheres.textbook_hits.float -->16481<!-- /figure -->
// or, for several lines a program prints, a fenced block right after a marker line
//     <!-- figure-block: stage01.showcase_output -->
//     ```
//     ...the lines, exactly...
//     ```
// This program computes every named figure from the library and reads every
// page under the folders it is given: a page whose value differs from the
// code's, or that names a figure this program does not know, is one line
//     page:line: figure NAME: the page says 'X', the code gives 'Y'
// and the exit code is 1. Names ending in .float or .double hold only for that
// rt::real and are checked in that build. A figure that needs a student's
// exercise that is not done yet (a kit) is not checked, nor, in a kit, a figure
// of a textbook method the student has written (tests/textbook_methods.hpp: the
// pages quote the reference's): the run names each on a line "SKIPPED: ..." and,
// when no figure is stale, exits 77, which ctest counts as skipped.
//
//     docs_figures REPO_ROOT            (reads REPO_ROOT/docs and REPO_ROOT/scenes)
//     docs_figures REPO_ROOT --print    (every figure and its value, for pasting)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <system_error>
#include <type_traits>
#include <variant>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/path_tracing/path_tracer.hpp>
#include <rt/camera/camera.hpp>
#include <rt/shading/dielectric.hpp>
#include <rt/output/encoding.hpp>
#include <rt/intersection/groups.hpp>
#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/core/random.hpp>
#include <rt/core/error.hpp>
#include <rt/output/encoded_output.hpp>
#include <rt/output/image_io.hpp>
#include <rt/camera/ray_image.hpp>
#include <rt/rendering/radiance.hpp>
#include <rt/shading/raytracer.hpp>
#include <rt/shading/refraction.hpp>
#include <rt/scene/scene.hpp>
#include <rt/input/scene_loader.hpp>
#include <rt/shading/shading.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/intersection/sphere_stable.hpp>
#include <rt/output/transfer.hpp>

#include "../stages/02_generate_rays/edge.hpp"
#include "../stages/common/textbook_groups.hpp"
#include "edge_leaks.hpp"
#include "path_scenes.hpp"
#include "reintersect.hpp"
#include "shadow_acne.hpp"
#include "slab_cases.hpp"
#include "sphere_accuracy.hpp"

namespace {

namespace fs = std::filesystem;

using figure_function = std::function<std::string()>;

std::string bytes_text(const rt::color& c, float gamma)
{
    return "(" + std::to_string(rt::to_byte(c.r, gamma)) + ", " + std::to_string(rt::to_byte(c.g, gamma)) + ", " +
           std::to_string(rt::to_byte(c.b, gamma)) + ")";
}

/// What stage 04's program counts on the showcase: the pixels where the groups
/// (build_groups, closest_hit_groups) with the textbook methods (stage 03's
/// quadratic, Moller-Trumbore) differ from the library's accelerator, by the
/// program's rule (stages/04_triangle/main.cpp): a miss on one side, another
/// shape, or depths t |d| more than 1e-4 apart relative. The reference's figures:
/// a student's quadratic may round the grazing pixel either way.
struct showcase_compare {
    std::size_t pixels = 0, leaks = 0, extra = 0, other = 0;
    int column = -1, row = -1;      // the first differing pixel (--pixel's column and row)
    double t_yours = 0, t_library = 0;
};

const showcase_compare& stage04_showcase_compare(const fs::path& root)
{
    if (!rt_test::exercises_are_the_reference) // a kit: skipped before its 460800 rays are traced
        throw rt_test::not_the_reference("your groups and textbook methods (stages 03 and 04) are yours here; the "
                                         "page quotes the reference's");
    static const showcase_compare result = [&] {
        const rt::scene s = rt::load_scene(root / "scenes" / "showcase.scene");
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
        const stage::textbook_groups mine(s);
        const rt::accelerator library(s);
        showcase_compare c;
        c.pixels = std::size_t(gen.nx) * std::size_t(gen.ny);
        for (int j = gen.ny - 1; j >= 0; --j) // the top row first, as the program counts
            for (int i = 0; i < gen.nx; ++i) {
                const rt::ray r = rt::pixel_ray(gen, i, j);
                rt::hit_record a, b;
                const bool hit_a = mine.closest_hit(r, 0, rt::infinity, a);
                const bool hit_b = library.closest_hit(r, 0, rt::infinity, b);
                const float length = float(glm::length(r.direction));
                const float depth_a = float(a.t) * length, depth_b = float(b.t) * length;
                bool differs = false;
                if (hit_b && !hit_a)
                    differs = ++c.leaks > 0;
                else if (hit_a && !hit_b)
                    differs = ++c.extra > 0;
                else if (hit_a && (a.shape != b.shape ||
                                   std::fabs(depth_a - depth_b) > 1e-4f * std::max(depth_a, depth_b)))
                    differs = ++c.other > 0;
                if (differs && c.column < 0) {
                    c.column = i;
                    c.row = gen.ny - 1 - j;
                    c.t_yours = double(a.t);
                    c.t_library = double(b.t);
                }
            }
        return c;
    }();
    return result;
}

/// The rays of the stage-02 program: the ray image of the showcase camera,
/// written with gamma 1; its centre pixel (column nx/2, row ny/2 from the top).
std::string showcase_ray_image_centre(const fs::path& root)
{
    const rt::scene s = rt::load_scene(root / "scenes" / "showcase.scene");
    const rt::image img = rt::render_ray_directions(rt::make_ray_generator(s.cam, s.width, s.height));
    return bytes_text(img.at(s.width / 2, s.height / 2), 1.0f);
}

/// A line stage02_generate_rays prints, formatted as it formats it.
std::string printed(const char* format, double a, double b = 0, double c = 0, double d = 0)
{
    char text[200];
    std::snprintf(text, sizeof text, format, a, b, c, d);
    return text;
}

/// The generator of the showcase scene's camera, as the stage-02 program makes it.
rt::ray_generator showcase_generator(const fs::path& root)
{
    const rt::scene s = rt::load_scene(root / "scenes" / "showcase.scene");
    return rt::make_ray_generator(s.cam, s.width, s.height);
}

/// The count stage03_sphere prints, "N of M rays hit": one ray per pixel,
/// the spheres in scene order through the closest-hit loop ([0, tmax], tmax
/// the nearest t so far).
template <class Hit>
std::string sphere_hits(const fs::path& scene_path, Hit hit)
{
    const rt::scene s = rt::load_scene(scene_path);
    std::vector<rt::sphere> spheres;
    for (const rt::shape& item : s.shapes)
        if (const rt::sphere* sp = std::get_if<rt::sphere>(&item))
            spheres.push_back(*sp);
    const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
    std::size_t hits = 0;
    for (int j = 0; j < gen.ny; ++j)
        for (int i = 0; i < gen.nx; ++i) {
            const rt::ray r = rt::pixel_ray(gen, i, j);
            rt::real tmax = std::numeric_limits<rt::real>::infinity();
            bool any = false;
            for (const rt::sphere& sphere : spheres) {
                rt::hit_record rec;
                if (hit(sphere, r, rt::real(0), tmax, rec)) {
                    tmax = rec.t;
                    any = true;
                }
            }
            hits += any ? 1 : 0;
        }
    return std::to_string(hits);
}

/// printf into a std::string (the stage programs print with printf).
template <class... Args>
std::string formatted(const char* format, Args... args)
{
    char text[256];
    std::snprintf(text, sizeof text, format, args...);
    return text;
}

/// What stage01_load_scene prints for a scene (stages/01_load_scene/main.cpp,
/// the same formats), from the library's loader and scene_bounds.
std::string stage01_output(const fs::path& root, const std::string& relative)
{
    const rt::scene s = rt::load_scene(root / relative);
    auto vector_line = [](const char* name, const rt::vec3& v) {
        return formatted("  %-8s %12.6g %12.6g %12.6g\n", name, double(v.x), double(v.y), double(v.z));
    };
    std::string out = "scene " + relative + "\n";
    out += formatted("image %d x %d, %d sample(s) per pixel, max depth %d\n", s.width, s.height, s.samples,
                     s.max_depth);
    const rt::camera& cam = s.cam;
    out += std::string("camera ") + rt::name_of(cam.kind) + "\n";
    out += vector_line("eye", cam.eye) + vector_line("look_at", cam.look_at) + vector_line("up", cam.up);
    if (cam.plane)
        out += formatted("  window   l %g r %g b %g t %g (as given)\n", double(cam.plane->l), double(cam.plane->r),
                         double(cam.plane->b), double(cam.plane->t));
    else if (cam.fov_degrees)
        out += formatted("  fov      %g degrees (vertical)\n", double(*cam.fov_degrees));
    out += formatted("  focal    %g\n", double(cam.focal_distance));
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
    out += formatted("shapes %zu: %zu sphere(s), %zu triangle(s), %zu mesh(es) with %zu triangle(s)\n",
                     s.shapes.size(), spheres, triangles, meshes, mesh_triangles);
    out += formatted("materials %zu, lights %zu\n", s.materials.size(), s.lights.size());
    const rt::aabb box = rt::scene_bounds(s);
    out += vector_line("min", box.lo) + vector_line("max", box.hi);
    out.pop_back(); // a block's last line has no newline
    return out;
}

/// The one-line message the loader gives for a bad scene `text` read as "bad.scene".
std::string load_message(const std::string& text)
{
    try {
        rt::load_scene_from_string(text, "bad.scene");
    } catch (const rt::exercise_not_done&) {
        throw;
    } catch (const rt::error& e) {
        return e.what();
    }
    return "(no error)";
}

/// The color the --pixel story of stages 05 to 08 prints for the showcase
/// scene: the ray through the centre of the pixel in column `column` from the
/// left and row `row` from the top (j = ny - 1 - row from the bottom), through
/// the library's accelerator, with `color(scene, accelerator, ray)`.
template <class Color>
rt::color showcase_pixel(const fs::path& root, int column, int row, Color color, int max_depth = -1)
{
    rt::scene s = rt::load_scene(root / "scenes" / "showcase.scene");
    if (max_depth >= 0) // --max-depth N
        s.max_depth = max_depth;
    const rt::accelerator accel(s);
    const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
    return color(s, accel, rt::pixel_ray(gen, column, s.height - 1 - row));
}

rt::color stage05_color(const rt::scene& s, const rt::accelerator& accel, const rt::ray& r)
{
    rt::hit_record hit;
    if (!accel.closest_hit(r, 0, std::numeric_limits<rt::real>::infinity(), hit))
        return s.background;
    return rt::direct_lighting(s, hit, r.direction, [](const rt::light_sample&) { return true; });
}

rt::color stage07_color(const rt::scene& s, const rt::accelerator& accel, const rt::ray& r)
{
    return rt::ray_color(s, accel, r);
}

/// Stage 09's color of the pixel in `column`, `row` (from the top) of
/// scenes/glass.scene, and the closest-hit and any-hit queries it took.
std::pair<rt::color, std::uint64_t> glass_pixel(const fs::path& root, int column, int row, int max_depth = -1)
{
    rt::scene s = rt::load_scene(root / "scenes" / "glass.scene");
    if (max_depth >= 0)
        s.max_depth = max_depth;
    const rt::accelerator accel(s);
    const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
    std::uint64_t queries = 0;
    const rt::color c = rt::ray_color_glass(s, rt::counting_accelerator{&accel, &queries},
                                            rt::pixel_ray(gen, column, s.height - 1 - row));
    return {c, queries};
}

/// Stage 10: the share of shadow rays from x that reach a sphere light (radius
/// 1, centre 5 above x) past a ball (radius 0.3, 2 above x), for n samples by
/// solid angle (the student's sample_sphere_light), against the closed form
/// (cos a - cos t_max) / (1 - cos t_max). The test's geometry.
std::string sphere_light_table()
{
    rt::light bulb;
    bulb.kind = rt::light_kind::sphere;
    bulb.position = rt::vec3(0, 0, 5);
    bulb.radius = 1;
    const double cos_max = std::sqrt(1 - 1.0 / 25), cos_a = std::sqrt(1 - 0.09 / 4);
    const double want = (cos_a - cos_max) / (1 - cos_max);
    std::string out = formatted("closed form %.5f\nsamples   share     error     sigma = sqrt(p (1 - p) / n)", want);
    rt::pcg32 rng(2026, 10);
    for (const int n : {100, 1000, 10000, 100000}) {
        int reach = 0;
        for (int k = 0; k < n; ++k) {
            const rt::real xi1 = rng.next_float(), xi2 = rng.next_float();
            const rt::vec3 y = rt::sample_light(bulb, rt::vec3(0), false, rt::vec2(xi1, xi2)).l;
            // the ray from the origin along y passes the ball (centre (0, 0, 2), radius 0.3) when
            // its angle to the axis exceeds asin(0.3 / 2)
            reach += double(y.z) < cos_a ? 1 : 0;
        }
        const double share = double(reach) / n;
        out += formatted("\n%7d   %.5f  %+.5f   %.5f", n, share, share - want, std::sqrt(want * (1 - want) / n));
    }
    return out;
}

/// Stage 10: the noise of a pixel in the middle of a penumbra (half the light
/// hidden, p = 1/2) estimated with n shadow rays: the standard deviation of
/// 4000 such estimates against sqrt(p (1 - p) / n), drawn with the student's
/// sample_rect_light (x below the square light [-1, 1]^2 at height 4, hidden
/// where the ray crosses height 2 left of x = 0).
std::string penumbra_noise_table()
{
    rt::light panel;
    panel.kind = rt::light_kind::rect;
    panel.position = rt::vec3(-1, -1, 4);
    panel.edge1 = rt::vec3(2, 0, 0);
    panel.edge2 = rt::vec3(0, 2, 0);
    rt::pcg32 rng(7, 10);
    std::string out = "samples   noise    sqrt(1/4 / n)";
    for (const int n : {1, 4, 16, 64, 256}) {
        const int trials = 4000;
        double sum = 0, square = 0;
        for (int k = 0; k < trials; ++k) {
            int reach = 0;
            for (int m = 0; m < n; ++m) {
                const rt::real xi1 = rng.next_float(), xi2 = rng.next_float();
                reach += rt::sample_light(panel, rt::vec3(0), false, rt::vec2(xi1, xi2)).l.x >= 0 ? 1 : 0;
            }
            const double estimate = double(reach) / n;
            sum += estimate;
            square += estimate * estimate;
        }
        const double mean = sum / trials;
        out += formatted("\n%7d   %.4f   %.4f", n, std::sqrt(square / trials - mean * mean), std::sqrt(0.25 / n));
    }
    return out;
}

/// Stage 11: inside the glowing cube (tests/path_scenes.hpp, Le 0.5), the mean
/// of 2000 paths of each strategy with roulette against Le / (1 - rho): the
/// table of docs/stages/11-going-further.md.
std::string glowing_cube_table()
{
    std::string out = "rho   Le/(1-rho)   cosine            nee               mis";
    for (const float rho : {0.4f, 0.7f, 0.9f}) {
        const rt::scene s = path_scenes::glowing_cube(rho, 0.5f);
        const rt::accelerator accel(s);
        const rt::emitter_list lights = rt::find_emitters(s);
        const rt::ray r{rt::vec3(rt::real(0.1), rt::real(-0.2), 0), glm::normalize(rt::vec3(0.3f, -0.2f, 1))};
        out += formatted("\n%.1f   %.4f      ", double(rho), 0.5 / (1 - double(rho)));
        for (const rt::path_strategy kind : {rt::path_strategy::cosine, rt::path_strategy::nee, rt::path_strategy::mis}) {
            rt::path_options o;
            o.strategy = kind;
            o.max_bounces = 1000;
            const path_scenes::running m = path_scenes::paths_along(s, accel, lights, r, o, 2000, 11);
            out += formatted("  %.4f +- %.4f", m.mean(), m.error());
        }
    }
    return out;
}

/// Stage 11: the RMSE of 300 means of N paths inside the glowing cube (rho
/// 0.6, MIS), and the least-squares slope of log RMSE against log N.
std::string path_slope_table()
{
    const rt::scene s = path_scenes::glowing_cube(0.6f, 0.5f);
    const rt::accelerator accel(s);
    const rt::emitter_list lights = rt::find_emitters(s);
    const rt::ray r{rt::vec3(0), glm::normalize(rt::vec3(0.2f, 0.1f, 1))};
    rt::path_options o;
    o.max_bounces = 1000;
    std::string out = "paths N   RMSE of the mean";
    std::vector<double> xs, ys;
    std::uint64_t seed = 100;
    for (const int n : {16, 64, 256, 1024}) {
        double squares = 0;
        for (int k = 0; k < 300; ++k) {
            const double e = path_scenes::paths_along(s, accel, lights, r, o, n, seed++).mean() - 1.25;
            squares += e * e;
        }
        const double rmse = std::sqrt(squares / 300);
        out += formatted("\n%7d   %.5f", n, rmse);
        xs.push_back(std::log(double(n)));
        ys.push_back(std::log(rmse));
    }
    double mx = 0, my = 0, sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < xs.size(); ++i) {
        mx += xs[i] / double(xs.size());
        my += ys[i] / double(ys.size());
    }
    for (std::size_t i = 0; i < xs.size(); ++i) {
        sxy += (xs[i] - mx) * (ys[i] - my);
        sxx += (xs[i] - mx) * (xs[i] - mx);
    }
    return out + formatted("\nslope     %.3f", sxy / sxx);
}

/// Stage 10: the radius in pixels of the circle of confusion of the centre of
/// ball `index` of scenes/soft.scene: aperture |1 - z / focus| at depth z along
/// the view, seen from the eye (ny / (2 z tan(fov / 2)) pixels per unit there).
std::string soft_blur_pixels(const fs::path& root, std::size_t index)
{
    const rt::scene s = rt::load_scene(root / "scenes" / "soft.scene");
    const rt::sphere& ball = std::get<rt::sphere>(s.shapes.at(index));
    const rt::vec3 view = glm::normalize(s.cam.look_at - s.cam.eye);
    const double z = double(glm::dot(ball.center - s.cam.eye, view));
    const double radius = double(s.lens.aperture) * std::fabs(1 - z / double(s.lens.focus));
    const double fov = double(s.cam.fov_degrees.value_or(45)) * 3.14159265358979323846 / 180;
    return formatted("%.1f", radius * s.height / (2 * z * std::tan(fov / 2)));
}

/// Schlick against the exact Fresnel reflectance at a boundary from index
/// `eta` into `eta_t`, for incidence angles in degrees.
std::string schlick_table(rt::real eta, rt::real eta_t, const std::vector<double>& angles)
{
    std::string out = "angle   Schlick   Fresnel   Schlick - Fresnel";
    for (const double degrees : angles) {
        const rt::real c = rt::real(std::cos(degrees * 3.14159265358979323846 / 180));
        const double schlick = double(rt::schlick_reflectance(c, eta, eta_t));
        const double fresnel = double(rt::fresnel_reflectance(c, eta, eta_t));
        out += formatted("\n%5g   %7.4f   %7.4f   %+8.4f", degrees, schlick, fresnel, schlick - fresnel);
    }
    return out;
}

/// "color (linear) (r, g, b)" as the story prints it (%.9g).
std::string story_color(const rt::color& c)
{
    return formatted("(%.9g, %.9g, %.9g)", double(c.r), double(c.g), double(c.b));
}

/// "stored bytes (clamped, gamma 2.2): r g b" of the stage 05-07 stories.
std::string story_bytes_gamma(const rt::color& c)
{
    return std::to_string(rt::to_byte(c.r, 2.2f)) + " " + std::to_string(rt::to_byte(c.g, 2.2f)) + " " +
           std::to_string(rt::to_byte(c.b, 2.2f));
}

/// The stage-08 story's lines after the color: exposed, tone mapped, stored bytes.
std::string stage08_story(const rt::color& linear, const rt::encoding& enc)
{
    auto text = [](const rt::color& c) {
        std::ostringstream out;
        out << double(c.r) << " " << double(c.g) << " " << double(c.b);
        return out.str();
    };
    std::ostringstream stops;
    stops << double(enc.exposure);
    const rt::color exposed = rt::apply_exposure(linear, enc.exposure);
    const rt::color mapped = rt::apply_tonemap(exposed, enc.tonemap);
    const std::array<std::uint8_t, 3> bytes = rt::encode_color(linear, enc);
    return "exposed (2^" + stops.str() + "): " + text(exposed) + "\ntone mapped (" + rt::name_of(enc.tonemap) +
           "): " + text(mapped) + "\nstored bytes (sRGB): " + std::to_string(bytes[0]) + " " +
           std::to_string(bytes[1]) + " " + std::to_string(bytes[2]);
}

/// One linear value through the stage-08 pipeline to its stored byte.
std::string pipeline_byte(float linear, rt::encoding enc)
{
    return std::to_string(rt::encode_color(rt::color(linear), enc)[0]);
}

rt::encoding srgb_clamp()
{
    return rt::encoding{};
}

rt::encoding plain_gamma(float gamma)
{
    rt::encoding enc;
    enc.transfer = rt::transfer_kind::gamma;
    enc.gamma = gamma;
    return enc;
}


void sphere_accuracy_figures(std::map<std::string, figure_function>& all, const std::string& p);
void shadow_acne_figures(std::map<std::string, figure_function>& all, const std::string& p);

/// "1e4" for 10000: the power of ten a table row is labelled with.
std::string power_of_ten(double x)
{
    return "1e" + std::to_string(int(std::lround(std::log10(x))));
}

/// The cells of docs/stages/03-going-further.md: the distance table and the
/// ground table, as tests/library_sphere_stable.cpp prints and asserts them
/// (the same functions, tests/sphere_accuracy.hpp), for this build's real.
/// (Both precisions' names are known, each computed in its own build only.)
void sphere_accuracy_figures(std::map<std::string, figure_function>& all)
{
    for (const std::string p : {".float", ".double"})
        sphere_accuracy_figures(all, p);
}

void sphere_accuracy_figures(std::map<std::string, figure_function>& all, const std::string& p)
{
    // computed once, on first use, for all the cells
    auto distances = std::make_shared<std::vector<rt_test::distance_row>>();
    auto grounds = std::make_shared<std::vector<rt_test::ground_row>>();
    auto distance_rows = [distances]() -> const std::vector<rt_test::distance_row>& {
        if (distances->empty())
            *distances = rt_test::distance_table();
        return *distances;
    };
    auto ground_rows = [grounds]() -> const std::vector<rt_test::ground_row>& {
        if (grounds->empty())
            *grounds = rt_test::ground_table();
        return *grounds;
    };
    using rt_test::cell;
    for (std::size_t k = 0; k < 6; ++k) {
        const std::string row = "stage03.distance_" + power_of_ten(std::pow(10.0, double(k + 1))) + ".";
        auto at = [distance_rows, k]() -> const rt_test::distance_row& { return distance_rows().at(k); };
        // a cell of the textbook's (the stage-03 exercise) is skipped in a kit (require_textbook)
        all[row + "centred" + p] = [at] {
            rt_test::require_textbook();
            return cell(at().centred[0]) + " / " + cell(at().centred[1]);
        };
        all[row + "off_centre" + p] = [at] {
            rt_test::require_textbook();
            return cell(at().off_centre[0]) + " / " + cell(at().off_centre[1]);
        };
        all[row + "grazing" + p] = [at] {
            rt_test::require_textbook();
            return cell(at().grazing[0]) + " / " + cell(at().grazing[1]);
        };
        all[row + "fan_textbook" + p] = [at] {
            rt_test::require_textbook();
            return rt_test::fan_cell(at().fan[0], at().miss_fan[0]);
        };
        all[row + "fan_stable" + p] = [at] { return rt_test::fan_cell(at().fan[1], at().miss_fan[1]); };
        all[row + "fan_textbook_depth_error" + p] = [at] {
            rt_test::require_textbook();
            return rt_test::depth_cell(at().fan[0].worst_depth_error);
        };
    }
    for (std::size_t k = 0; k < 8; ++k) {
        const double R = std::pow(10.0, double(2 + k / 2));
        const std::string row = "stage03.ground_" + power_of_ten(R) + (k % 2 == 0 ? "_h1." : "_h0_25.");
        auto at = [ground_rows, k]() -> const rt_test::ground_row& { return ground_rows().at(k); };
        all[row + "exact_t" + p] = [at] { return rt_test::exact_text(at().exact); };
        all[row + "textbook" + p] = [at] {
            rt_test::require_textbook();
            return cell(at().result[0]);
        };
        all[row + "chapter" + p] = [at] { return cell(at().chapter); };
        all[row + "rt" + p] = [at] { return cell(at().result[1]); };
    }
    // the prose: the worst grazing ray of the stable method along the axis, the fan's size, the bound
    all["stage03.grazing_stable_worst"] = [distance_rows] {
        rt_test::outcome worst;
        for (const rt_test::distance_row& row : distance_rows())
            if (row.grazing[1].ulps >= worst.ulps)
                worst = row.grazing[1];
        return cell(worst);
    };
    all["stage03.fan_size"] = [] { return std::to_string(rt_test::fan_size); };
    all["stage03.ulp_bound"] = [] { return std::to_string(int(rt_test::ulp_bound)); };
}

/// The acne table of docs/stages/06-shadows.md (float build), as
/// tests/stage06_shadows.cpp prints and asserts it (tests/shadow_acne.hpp):
/// per row, the lit points, the robust method's acne (the stage-06 exercise:
/// skipped in a kit where it is not done) and the fixed epsilon's. A row that
/// stands for several settings ("1e-3 ... 1e1") gives their common value, or
/// all of them when they differ.
void shadow_acne_figures(std::map<std::string, figure_function>& all)
{
    for (const std::string p : {".float", ".double"})
        shadow_acne_figures(all, p);
}

void shadow_acne_figures(std::map<std::string, figure_function>& all, const std::string& p)
{
    struct group {
        std::string name;
        bool moved;
        int first, last;
    };
    std::vector<group> groups = {{"scale_1e-3_to_1e1", false, -3, 1}, {"offset_1e-3_to_1e3", true, -3, 3}};
    for (int e = 2; e <= 5; ++e)
        groups.push_back({"scale_1e" + std::to_string(e), false, e, e});
    for (int e = 4; e <= 5; ++e)
        groups.push_back({"offset_1e" + std::to_string(e), true, e, e});
    using count_of = int rt_test::shadow_count::*;
    for (const group& g : groups) {
        auto measure = [g](bool robust, count_of field) {
            std::vector<int> values;
            for (int e = g.first; e <= g.last; ++e) {
                rt_test::acne_setting set;
                set.moved = g.moved;
                (g.moved ? set.offset_exponent : set.scale_exponent) = e;
                const rt_test::shadow_count c =
                    robust ? rt_test::count_shadow_errors(set.scene(), rt_test::robust_visible)
                           : rt_test::count_shadow_errors(set.scene(), rt_test::fixed_epsilon_visible);
                values.push_back(c.*field);
            }
            std::string text = std::to_string(values.front());
            if (std::any_of(values.begin(), values.end(), [&](int v) { return v != values.front(); }))
                for (std::size_t k = 1; k < values.size(); ++k)
                    text += ", " + std::to_string(values[k]);
            return text;
        };
        const std::string row = "stage06.acne." + g.name + ".";
        all[row + "lit" + p] = [measure] { return measure(false, &rt_test::shadow_count::lit_points); };
        all[row + "robust" + p] = [measure] { return measure(true, &rt_test::shadow_count::acne); };
        all[row + "fixed" + p] = [measure] { return measure(false, &rt_test::shadow_count::acne); };
    }
}

/// 984000 as "984,000", as the pages write counts.
std::string with_commas(long n)
{
    std::string digits = std::to_string(n), text;
    for (std::size_t k = 0; k < digits.size(); ++k) {
        if (k > 0 && (digits.size() - k) % 3 == 0)
            text += ',';
        text += digits[k];
    }
    return text;
}

/// The reintersection counts of docs/stages/06-going-further.md, pbrt's
/// 1000 shapes x 1000 rays, as tests/library_reintersect.cpp prints and
/// asserts them (tests/reintersect.hpp): for each kind of shape and row, the
/// failures and the rays; the mixed-magnitudes case; and the failures of the
/// renderer's own rows summed.
void reintersect_figures(std::map<std::string, figure_function>& all, const std::string& p)
{
    namespace ri = rt_test::reintersect;
    const char* row_keys[ri::row_count] = {"spawn_random", "spawn_to_point", "pbr_to_point", "rtg_front", "rtg_to_point",
                                           "shadow_robust", "shadow_rtg", "mirror_robust", "mirror_rtg"};
    auto triangles = std::make_shared<std::vector<ri::reintersection>>();
    auto spheres = std::make_shared<std::vector<ri::reintersection>>();
    auto of = [](const std::shared_ptr<std::vector<ri::reintersection>>& cache, bool is_triangles) {
        return [cache, is_triangles]() -> const ri::reintersection& {
            if (cache->empty())
                cache->push_back(is_triangles ? ri::triangles(1000, 1000) : ri::spheres(1000, 1000));
            return cache->front();
        };
    };
    for (const auto& [kind, result] : {std::make_pair(std::string("triangles"), of(triangles, true)),
                                      std::make_pair(std::string("spheres"), of(spheres, false))}) {
        const auto get = result;
        for (int k = 0; k < ri::row_count; ++k) {
            const std::string row = "stage06.reintersect." + kind + "." + row_keys[k] + ".";
            all[row + "failures" + p] = [get, k] { return with_commas(get().rows[k].failures); };
            all[row + "rays" + p] = [get, k] { return with_commas(get().rows[k].rays); };
        }
        all["stage06.reintersect." + kind + ".robust_rows_failures" + p] = [get] {
            long failures = 0;
            for (int k = 0; k < ri::row_count; ++k)
                failures += ri::row_is_robust[k] ? get().rows[k].failures : 0;
            return with_commas(failures);
        };
    }
    auto mixed = std::make_shared<std::vector<ri::mixed_result>>();
    auto mixed_result = [mixed]() -> const ri::mixed_result& {
        if (mixed->empty())
            mixed->push_back(ri::mixed_magnitudes());
        return mixed->front();
    };
    all["stage06.reintersect.mixed.rtg_failures" + p] = [mixed_result] { return with_commas(mixed_result().rtg.failures); };
    all["stage06.reintersect.mixed.rays" + p] = [mixed_result] { return with_commas(mixed_result().rtg.rays); };
    all["stage06.reintersect.mixed.spawn_failures" + p] = [mixed_result] { return with_commas(mixed_result().robust.failures); };
}

void reintersect_figures(std::map<std::string, figure_function>& all)
{
    for (const std::string p : {".float", ".double"})
        reintersect_figures(all, p);
}

std::map<std::string, figure_function> figures(const fs::path& root)
{
    std::map<std::string, figure_function> all;
    all["stage02.showcase_centre_bytes"] = [root] { return showcase_ray_image_centre(root); };
    // what stage02_generate_rays prints for scenes/showcase.scene (its "%g" lines)
    all["stage02.showcase.v"] = [root] {
        const rt::frame f = showcase_generator(root).basis;
        return printed("%g %g %g", double(f.v.x), double(f.v.y), double(f.v.z));
    };
    all["stage02.showcase.w"] = [root] {
        const rt::frame f = showcase_generator(root).basis;
        return printed("%g %g %g", double(f.w.x), double(f.w.y), double(f.w.z));
    };
    all["stage02.showcase.window"] = [root] {
        const rt::window w = showcase_generator(root).plane;
        return printed("l %g r %g b %g t %g", double(w.l), double(w.r), double(w.b), double(w.t));
    };
    // and with --edge (stages/02_generate_rays/edge.hpp), which needs the sampling exercises
    all["stage02.edge.pixels"] = [root] {
        return std::to_string(stage::render_edge(showcase_generator(root)).edge_pixels);
    };
    all["stage02.edge.rms_centre.float"] = [root] {
        return printed("%.4f", stage::render_edge(showcase_generator(root)).rms_centre);
    };
    all["stage02.edge.rms_one.float"] = [root] {
        return printed("%.4f", stage::render_edge(showcase_generator(root)).rms_one);
    };
    all["stage02.edge.rms_sixteen.float"] = [root] {
        return printed("%.4f", stage::render_edge(showcase_generator(root)).rms_sixteen);
    };
    const fs::path far = root / "scenes" / "far-spheres.scene";
    for (const char* precision : {"float", "double"}) {
        const std::string p = precision;
        all["stage03.far_spheres.textbook_hits." + p] = [far] { return sphere_hits(far, rt::hit_sphere_textbook); };
        all["stage03.far_spheres.stable_hits." + p] = [far] { return sphere_hits(far, rt::hit_sphere); };
    }
    // stage 01: the program's output for the showcase scene, and one message per camera rule
    all["stage01.showcase_output"] = [root] { return stage01_output(root, "scenes/showcase.scene"); };
    all["stage01.message.unknown_keyword"] = [] { return load_message("sphere\nspere radius 1\n"); };
    for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
             {"eye_is_look_at", "camera perspective eye 1 1 1 look_at 1 1 1\n"},
             {"up_parallel", "camera perspective eye 0 0 5 look_at 0 0 0 up 0 0 2\n"},
             {"up_zero", "camera perspective up 0 0 0\n"},
             {"fov_zero", "camera perspective fov 0\n"},
             {"fov_180", "camera perspective fov 180\n"},
             {"fov_orthographic", "camera orthographic fov 60\n"},
             {"window_empty", "camera orthographic window 1 1 -1 1\n"},
             {"focal_zero", "camera perspective focal 0\n"},
             {"fov_and_window", "camera perspective fov 60 window -1 1 -1 1\n"},
             {"second_camera", "camera perspective\ncamera orthographic\n"},
             {"camera_type", "camera perspektive\n"}}) {
        const std::string scene_text = text;
        all["stage01.message." + name] = [scene_text] { return load_message(scene_text); };
    }
    // stages 05, 07 and 08: the --pixel stories of the showcase scene (float build)
    all["stage05.showcase_320_180.color.float"] = [root] {
        return story_color(showcase_pixel(root, 320, 180, stage05_color));
    };
    all["stage05.showcase_320_180.bytes.float"] = [root] {
        return story_bytes_gamma(showcase_pixel(root, 320, 180, stage05_color));
    };
    all["stage05.showcase_330_150.color.float"] = [root] {
        return story_color(showcase_pixel(root, 330, 150, stage05_color));
    };
    for (const auto& [column, row] : std::vector<std::pair<int, int>>{{330, 150}, {290, 150}, {320, 140}}) {
        const int c = column, r = row;
        const std::string at = std::to_string(c) + "_" + std::to_string(r);
        all["stage07.showcase_" + at + ".color.float"] = [root, c, r] {
            return story_color(showcase_pixel(root, c, r, stage07_color));
        };
        all["stage07.showcase_" + at + ".bytes.float"] = [root, c, r] {
            return story_bytes_gamma(showcase_pixel(root, c, r, stage07_color));
        };
    }
    all["stage07.showcase_330_150.color_depth_0.float"] = [root] {
        return story_color(showcase_pixel(root, 330, 150, stage07_color, 0));
    };
    all["stage08.showcase_290_150.story.float"] = [root] {
        return stage08_story(showcase_pixel(root, 290, 150, stage07_color), rt::encoding{});
    };
    all["stage08.showcase_290_150.story_reinhard.float"] = [root] {
        rt::encoding enc;
        enc.exposure = 1.0f;
        enc.tonemap = rt::tonemap_kind::reinhard;
        return stage08_story(showcase_pixel(root, 290, 150, stage07_color), enc);
    };
    // stage 09: Schlick against Fresnel, and the --pixel story of the glass scene
    all["stage09.schlick_air_to_glass"] = [] {
        return schlick_table(1, rt::real(1.5), {0, 45, 60, 80, 85, 89});
    };
    all["stage09.schlick_glass_to_air"] = [] {
        return schlick_table(rt::real(1.5), 1, {0, 30, 35, 40, 41, 42});
    };
    all["stage09.critical_angle"] = [] {
        return formatted("%.1f", std::asin(1 / 1.5) * 180 / 3.14159265358979323846);
    };
    all["stage09.glass_180_200.color.float"] = [root] { return story_color(glass_pixel(root, 180, 200).first); };
    all["stage09.glass_180_200.bytes.float"] = [root] { return story_bytes_gamma(glass_pixel(root, 180, 200).first); };
    all["stage09.glass_180_200.queries"] = [root] { return std::to_string(glass_pixel(root, 180, 200).second); };
    all["stage09.glass_180_200.color_depth_1.float"] = [root] {
        return story_color(glass_pixel(root, 180, 200, 1).first);
    };
    // stage 10: Monte Carlo convergence, the penumbra's noise, the lens's blur in soft.scene
    all["stage10.sphere_light_share"] = [] { return sphere_light_table(); };
    all["stage10.penumbra_noise"] = [] { return penumbra_noise_table(); };
    // the share of the shadow rays that pass a disc of radius 0.3 at height 2 (the test's closed form)
    all["stage10.disc_share"] = [] {
        const double cos_max = std::sqrt(1 - 1.0 / 25), cos_disc = 2 / std::sqrt(4 + 0.09);
        return formatted("%.6f", (cos_disc - cos_max) / (1 - cos_max));
    };
    // stage 11: the glowing cube's closed form against each strategy, and the N^-1/2 law
    all["stage11.glowing_cube.float"] = [] { return glowing_cube_table(); };
    all["stage11.slope.float"] = [] { return path_slope_table(); };
    all["stage10.soft.red_blur_pixels"] = [root] { return soft_blur_pixels(root, 1); };
    all["stage10.soft.green_blur_pixels"] = [root] { return soft_blur_pixels(root, 2); };
    // the student's groups over the showcase: its items (library), its nodes (the exercise build_groups)
    all["stage04.showcase.group_items"] = [root] {
        return std::to_string(rt::group_items(rt::load_scene(root / "scenes" / "showcase.scene")).size());
    };
    all["stage04.showcase.group_nodes"] = [root] {
        return std::to_string(
            rt::build_groups(rt::group_items(rt::load_scene(root / "scenes" / "showcase.scene"))).nodes.size());
    };
    // the program's --compare on the showcase, with the reference's groups and textbook methods
    all["stage04.showcase.compare.float"] = [root] {
        const showcase_compare& c = stage04_showcase_compare(root);
        return std::to_string(c.leaks + c.extra + c.other) + " of " + std::to_string(c.pixels) +
               " pixels differ (" + std::to_string(c.leaks) + " leaked through your triangles: the library hits, "
               "yours misses; " + std::to_string(c.extra) + " hit only with yours; " + std::to_string(c.other) +
               " hit a different shape or depth)";
    };
    all["stage04.showcase.compare_pixel.float"] = [root] {
        const showcase_compare& c = stage04_showcase_compare(root);
        return "(" + std::to_string(c.column) + ", " + std::to_string(c.row) + ")";
    };
    all["stage04.showcase.compare_t.float"] = [root] {
        const showcase_compare& c = stage04_showcase_compare(root);
        return printed("t = %g against the library's stable %g", c.t_yours, c.t_library);
    };
    // the slab test's failures (library_slab.cpp): the textbook form is stage 04's hit_box_textbook
    all["stage04.slab.face_plane_rays"] = [] { return std::to_string(rt_test::face_plane_rays().size()); };
    all["stage04.slab.face_plane_rays.textbook_misses"] = [] {
        rt_test::require_textbook_slab();
        return std::to_string(rt_test::misses(rt_test::face_plane_rays(), rt_test::textbook_hits));
    };
    all["stage04.slab.face_plane_rays.robust_misses"] = [] {
        return std::to_string(rt_test::misses(rt_test::face_plane_rays(), rt_test::robust_hits));
    };
    all["stage04.slab.edge_rays"] = [] { return std::to_string(rt_test::edge_rays().size()); };
    for (const char* precision : {"float", "double"})
        all["stage04.slab.edge_rays.textbook_misses." + std::string(precision)] = [] {
            rt_test::require_textbook_slab();
            return std::to_string(rt_test::misses(rt_test::edge_rays(), rt_test::textbook_hits));
        };
    all["stage04.slab.edge_rays.robust_misses"] = [] {
        return std::to_string(rt_test::misses(rt_test::edge_rays(), rt_test::robust_hits));
    };
    // the watertight test with its edge functions fused (library_watertight.cpp, edge_leaks.hpp), counted once
    auto edge_leaks = std::make_shared<std::vector<rt_test::edge_leak_count>>();
    auto leaks = [edge_leaks]() -> const rt_test::edge_leak_count& {
        if (edge_leaks->empty())
            edge_leaks->push_back(rt_test::icosphere_edge_leaks());
        return edge_leaks->front();
    };
    for (const std::string precision : {".float", ".double"}) {
        all["stage04.watertight.edge_rays" + precision] = [leaks] { return std::to_string(leaks().rays); };
        all["stage04.watertight.fused_leaks" + precision] = [leaks] { return std::to_string(leaks().fused_leaks); };
        all["stage04.watertight.library_leaks" + precision] = [leaks] {
            return std::to_string(leaks().library_leaks);
        };
    }
    all["stage03.far_spheres.rays"] = [far] {
        const rt::scene s = rt::load_scene(far);
        return std::to_string(s.width * s.height);
    };
    sphere_accuracy_figures(all); // (long double is the exact reference on every supported platform)
    shadow_acne_figures(all);
    reintersect_figures(all);
    all["stage08.worked_example_byte"] = [] {
        rt::encoding enc;
        enc.exposure = 1.0f;
        enc.tonemap = rt::tonemap_kind::reinhard;
        return pipeline_byte(0.5f, enc);
    };
    for (const auto& [name, x] : std::vector<std::pair<std::string, float>>{
             {"0_18", 0.18f}, {"0_00132", 0.00132f}, {"0_001", 0.001f}}) {
        const float value = x;
        all["stage08.srgb_byte_at_" + name] = [value] { return pipeline_byte(value, srgb_clamp()); };
        all["stage08.gamma22_byte_at_" + name] = [value] { return pipeline_byte(value, plain_gamma(2.2f)); };
    }
    return all;
}

bool holds_in_this_build(const std::string& name)
{
    const bool is_float = std::is_same<rt::real, float>::value;
    auto ends_with = [&](const std::string& tail) {
        return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
    };
    if (ends_with(".float"))
        return is_float;
    if (ends_with(".double"))
        return !is_float;
    return true;
}

} // namespace

int main(int argc, char** argv)
{
    const bool print = argc == 3 && std::string(argv[2]) == "--print";
    if (argc < 2 || argc > 3 || (argc == 3 && !print) || std::string(argv[1]).rfind("-", 0) == 0) {
        std::cerr << "usage: docs_figures REPO_ROOT [--print]   (REPO_ROOT holds docs/ and scenes/)\n";
        return 2;
    }
    const fs::path root = argv[1];
    std::error_code missing;
    if (!fs::is_directory(root / "docs", missing)) {
        std::cerr << "docs_figures: expected a folder " << (root / "docs").string()
                  << " (the repository's root as the first argument), found none\n";
        return 2;
    }
    const std::map<std::string, figure_function> known = figures(root);
    std::map<std::string, std::string> computed; // cache: each figure once
    std::vector<std::string> skipped;
    auto value_of = [&](const std::string& name) -> const std::string* {
        auto at = computed.find(name);
        if (at != computed.end())
            return &at->second;
        try {
            return &(computed[name] = known.at(name)());
        } catch (const rt::exercise_not_done& e) {
            skipped.push_back(name + " (" + e.what() + ")");
            return nullptr;
        } catch (const rt_test::not_the_reference& e) {
            skipped.push_back(name + " (" + e.what() + ")");
            return nullptr;
        }
    };
    if (print) {
        for (const auto& entry : known)
            if (holds_in_this_build(entry.first))
                if (const std::string* v = value_of(entry.first))
                    std::cout << entry.first << " = " << *v << "\n";
        return 0;
    }

    const std::regex marker(R"(<!-- figure: ([A-Za-z0-9_.]+) -->(.*?)<!-- /figure -->)");
    std::vector<fs::path> pages;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / "docs"))
        if (e.is_regular_file() && e.path().extension() == ".md")
            pages.push_back(e.path());
    std::sort(pages.begin(), pages.end());
    const std::regex block_marker(R"(^<!-- figure-block: ([A-Za-z0-9_.]+) -->\s*$)");
    int quoted = 0, checked = 0, failures = 0;
    // One quoted figure: the page's text against the code's value.
    // `block_page`/`block_line`: for a block, the page and the line number of its first line
    auto compare = [&](const std::string& where, const std::string& name, const std::string& said,
                       const std::string& block_page = "", std::size_t block_line = 0) {
        ++quoted;
        if (!known.count(name)) {
            std::cout << where << ": figure " << name << ": expected a figure docs_figures computes, found "
                      << "an unknown name; add it to tests/docs_figures.cpp\n";
            ++failures;
            return;
        }
        if (!holds_in_this_build(name))
            return;
        const std::string* code = value_of(name);
        if (!code)
            return;
        ++checked;
        if (said == *code)
            return;
        ++failures;
        if (said.find('\n') == std::string::npos && code->find('\n') == std::string::npos) {
            std::cout << where << ": figure " << name << ": the page says '" << said << "', the code gives '" << *code
                      << "'\n";
            return;
        }
        // a block: one line for its first line that differs
        std::istringstream page_lines(said), code_lines(*code);
        std::string page_line, code_line;
        for (int k = 1;; ++k) {
            const bool more_page = bool(std::getline(page_lines, page_line));
            const bool more_code = bool(std::getline(code_lines, code_line));
            if (!more_page && !more_code)
                break;
            if (more_page != more_code || page_line != code_line) {
                std::cout << block_page << ":" << block_line + std::size_t(k) - 1 << ": figure " << name
                          << ": line " << k << " of the block says '"
                          << (more_page ? page_line : "(nothing)") << "', the code gives '"
                          << (more_code ? code_line : "(nothing)") << "'\n";
                break;
            }
        }
    };
    for (const fs::path& page : pages) {
        std::ifstream in(page);
        std::vector<std::string> lines;
        for (std::string line; std::getline(in, line);)
            lines.push_back(line);
        const std::string name_of_page = fs::relative(page, root).generic_string();
        for (std::size_t k = 0; k < lines.size(); ++k) {
            const std::string where = name_of_page + ":" + std::to_string(k + 1);
            std::smatch block;
            if (std::regex_match(lines[k], block, block_marker)) {
                // the fenced block on the next line, up to its closing fence, is the figure
                const std::string name = block[1];
                if (k + 1 >= lines.size() || lines[k + 1].rfind("```", 0) != 0) {
                    std::cout << where << ": figure " << name << ": expected a fenced block (```) on the next line, "
                              << "found " << (k + 1 < lines.size() ? "'" + lines[k + 1] + "'" : "the end of the page")
                              << "\n";
                    ++failures;
                    continue;
                }
                std::size_t end = k + 2;
                while (end < lines.size() && lines[end] != "```")
                    ++end;
                std::string said;
                for (std::size_t b = k + 2; b < end; ++b)
                    said += (b > k + 2 ? "\n" : "") + lines[b];
                compare(where, name, said, name_of_page, k + 3);
                k = end;
                continue;
            }
            for (std::sregex_iterator m(lines[k].begin(), lines[k].end(), marker), stop; m != stop; ++m)
                compare(where, (*m)[1], (*m)[2]);
        }
    }
    if (quoted == 0) {
        std::cout << "expected figures marked <!-- figure: NAME -->VALUE<!-- /figure --> under " << (root / "docs")
                  << ", found none\n";
        return 1;
    }
    std::cout << checked << " of " << quoted << " quoted figures checked against the code, " << failures
              << " stale\n";
    for (const std::string& s : skipped)
        std::cout << "SKIPPED: " << s << "\n";
    if (failures > 0)
        return 1;
    return skipped.empty() ? 0 : 77; // a figure not checked: the test is not a pass
}
