// path_story_text.hpp - stage 11's --pixel: the render's first sample of one
// pixel traced again with rt::path_story_recorder, and its story told bounce by
// bounce in words (--pixel) or as JSON (--pixel-json).
#pragma once

#include <cstddef>
#include <cstdint>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>

#include <rt/core/enum_names.hpp>
#include <rt/core/error.hpp>
#include <rt/core/random.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/path_tracing/path_story.hpp>
#include <rt/path_tracing/path_tracer.hpp>
#include <rt/rendering/radiance.hpp>
#include <rt/scene/scene.hpp>

#include "stage_main.hpp"

namespace stage {

/// A point, direction or color (rt::vec3 or rt::color, float or double) as "(x, y, z)".
template <class T>
std::string path_text(const glm::vec<3, T, glm::defaultp>& v)
{
    std::ostringstream out;
    out << std::setprecision(6) << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return out.str();
}

/// A path's story, bounce by bounce, in words.
inline void print_path_story(std::ostream& out, const rt::path_story& st, const rt::scene& s, const rt::ray& camera,
                             int column, int row, const rt::path_options& o)
{
    out << "pixel (" << column << ", " << row << "): the render's first sample, strategy " << rt::name_of(o.strategy)
        << (o.roulette ? ", Russian roulette from bounce " + std::to_string(o.roulette_start) : ", no roulette")
        << "\n";
    out << "  camera ray from " << path_text(camera.origin) << " along " << path_text(camera.direction) << "\n";
    int bounce = 0;
    for (const rt::path_vertex& v : st.vertices) {
        const rt::material& m = s.material_of(v.material);
        out << "  bounce " << bounce << ": hit " << path_text(v.point) << ", material '" << m.name << "' (kd "
            << path_text(m.kd) << "), throughput " << path_text(v.throughput) << "\n";
        if (v.emitted != rt::color(0.0f))
            out << "    it glows: Le " << path_text(v.emitted) << ", weight " << v.emitted_weight
                << (v.emitted_weight == 0 ? " (next-event estimation counted it already)" : "") << "\n";
        if (v.light_sampled) {
            out << "    next-event estimation: the light point " << path_text(v.light_point);
            if (v.light_estimate == rt::color(0.0f) && m.kd == rt::color(0.0f))
                out << ": the surface reflects nothing (kd 0)\n";
            else if (v.light_estimate == rt::color(0.0f))
                out << " is below the surface, or the surface is behind the light: nothing\n";
            else if (!v.light_visible)
                out << " is hidden: the shadow ray is blocked\n";
            else
                out << " is visible: estimate " << path_text(v.light_estimate) << ", weight " << v.light_weight << "\n";
        }
        out << "    adds " << path_text(v.added) << "\n";
        if (v.bounced)
            out << "    next direction " << path_text(v.direction) << ", pdf " << v.pdf << ", weight f cos / pdf "
                << path_text(v.weight) << "\n";
        if (v.roulette_played)
            out << "    Russian roulette: " << (v.survived ? "goes on" : "ends here") << "\n";
        ++bounce;
    }
    if (st.escaped)
        out << "  the path leaves the scene: background " << path_text(s.background) << " adds "
            << path_text(st.background_added)
            << "\n";
    out << "  " << st.ending << "\n";
    out << "  radiance of this sample: " << path_text(st.radiance) << "\n";
}

inline void print_path_story_json(std::ostream& out, const rt::path_story& st, const rt::scene& s, int column, int row)
{
    auto v3 = [](const rt::vec3& v) {
        std::ostringstream o;
        o << std::setprecision(9) << "[" << v.x << ", " << v.y << ", " << v.z << "]";
        return o.str();
    };
    auto c3 = [&](const rt::color& c) { return v3(rt::vec3(rt::real(c.r), rt::real(c.g), rt::real(c.b))); };
    out << "{\"pixel\": [" << column << ", " << row << "], \"bounces\": [";
    for (std::size_t i = 0; i < st.vertices.size(); ++i) {
        const rt::path_vertex& v = st.vertices[i];
        out << (i ? ", " : "") << "{\"point\": " << v3(v.point) << ", \"material\": \""
            << rt::detail::printable(s.material_of(v.material).name) << "\", \"throughput\": " << c3(v.throughput)
            << ", \"emitted\": " << c3(v.emitted) << ", \"emitted_weight\": " << v.emitted_weight
            << ", \"light_visible\": " << (v.light_visible ? "true" : "false") << ", \"light_estimate\": "
            << c3(v.light_estimate) << ", \"light_weight\": " << v.light_weight << ", \"added\": " << c3(v.added)
            << ", \"direction\": " << v3(v.direction) << ", \"pdf\": " << v.pdf << ", \"survived\": "
            << (v.survived ? "true" : "false") << "}";
    }
    out << "], \"escaped\": " << (st.escaped ? "true" : "false") << ", \"radiance\": " << c3(st.radiance) << "}\n";
}

/// The story of the render's first sample of `pixel`: the same generator, so the
/// same random numbers, as render_paths draws for it; printed to `out`.
template <class Accelerator>
void tell_path_story(std::ostream& out, const rt::scene& s, const Accelerator& accel, const rt::emitter_list& lights,
                     const rt::ray_source& rays, std::uint64_t seed, const pixel_request& pixel,
                     const rt::path_options& o)
{
    if (pixel.column >= s.width || pixel.row >= s.height)
        throw rt::error("option --pixel: expected a pixel of the " + std::to_string(s.width) + "x" +
                        std::to_string(s.height) + " image, found (" + std::to_string(pixel.column) + ", " +
                        std::to_string(pixel.row) + ")");
    const std::uint64_t index = std::uint64_t(pixel.row) * std::uint64_t(s.width) + std::uint64_t(pixel.column);
    rt::pcg32 rng = rt::seeded_generator(seed, index, 1, rt::integrator_stream);
    const rt::real fx = rng.next_float(), fy = rng.next_float();
    const rt::ray camera = rays(rt::real(pixel.column) + fx, rt::real(s.height - 1 - pixel.row) + fy);
    rt::path_story story;
    (void)rt::path_radiance(s, accel, lights, camera, rng, o, rt::path_story_recorder{&story});
    if (pixel.json)
        print_path_story_json(out, story, s, pixel.column, pixel.row);
    else
        print_path_story(out, story, s, camera, pixel.column, pixel.row, o);
}

} // namespace stage
