// docs_figures.cpp - no figure in the docs can go stale (label docs).
//
// A page quotes a number the code produces as
//     <!-- figure: stage03.far_spheres.textbook_hits.float -->16481<!-- /figure -->
// This program computes every named figure from the library and reads every
// page under the folders it is given: a page whose value differs from the
// code's, or that names a figure this program does not know, is one line
//     page:line: figure NAME: the page says 'X', the code gives 'Y'
// and the exit code is 1. Names ending in .float or .double hold only for that
// rt::real and are checked in that build. A figure that needs a student's
// exercise that is not done yet (a kit) is skipped, and the run says SKIPPED.
//
//     docs_figures REPO_ROOT            (reads REPO_ROOT/docs and REPO_ROOT/scenes)
//     docs_figures REPO_ROOT --print    (every figure and its value, for pasting)
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <rt/camera.hpp>
#include <rt/encoding.hpp>
#include <rt/error.hpp>
#include <rt/image_io.hpp>
#include <rt/ray_image.hpp>
#include <rt/scene.hpp>
#include <rt/scene_loader.hpp>
#include <rt/sphere.hpp>
#include <rt/sphere_stable.hpp>
#include <rt/transfer.hpp>

#include "../stages/02_generate_rays/edge.hpp"

namespace {

namespace fs = std::filesystem;

using figure_function = std::function<std::string()>;

std::string bytes_text(const rt::color& c, float gamma)
{
    return "(" + std::to_string(rt::to_byte(c.r, gamma)) + ", " + std::to_string(rt::to_byte(c.g, gamma)) + ", " +
           std::to_string(rt::to_byte(c.b, gamma)) + ")";
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
    if (argc < 2) {
        std::cerr << "usage: docs_figures REPO_ROOT [--print]\n";
        return 2;
    }
    const fs::path root = argv[1];
    const bool print = argc > 2 && std::string(argv[2]) == "--print";
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
    int quoted = 0, checked = 0, failures = 0;
    for (const fs::path& page : pages) {
        std::ifstream in(page);
        std::string line;
        for (int number = 1; std::getline(in, line); ++number)
            for (std::sregex_iterator m(line.begin(), line.end(), marker), end; m != end; ++m) {
                ++quoted;
                const std::string name = (*m)[1];
                const std::string said = (*m)[2];
                const std::string where = fs::relative(page, root).generic_string() + ":" + std::to_string(number);
                if (!known.count(name)) {
                    std::cout << where << ": figure " << name << ": expected a figure docs_figures computes, found "
                              << "an unknown name; add it to tests/docs_figures.cpp\n";
                    ++failures;
                    continue;
                }
                if (!holds_in_this_build(name))
                    continue;
                const std::string* code = value_of(name);
                if (!code)
                    continue;
                ++checked;
                if (said != *code) {
                    std::cout << where << ": figure " << name << ": the page says '" << said << "', the code gives '"
                              << *code << "'\n";
                    ++failures;
                }
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
    return failures == 0 ? 0 : 1;
}
