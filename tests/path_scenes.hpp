// path_scenes.hpp - scenes whose path-traced radiance is known exactly, and
// the statistics that compare a Monte Carlo mean with it (stage 11's suite and
// tests/library_path_tracing.cpp). Every scene is built in code: no scene file
// (whose camera statement is stage 01's) and no camera (stage 02's); the rays
// are the tests' own.
#pragma once

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include <rt/bvh/accelerator.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/path_tracing/path_tracer.hpp>
#include <rt/core/random.hpp>
#include <rt/scene/scene.hpp>

namespace path_scenes {

/// A running mean and sample variance (two sums, in double).
struct running {
    double s1 = 0, s2 = 0;
    long n = 0;
    void add(double x)
    {
        s1 += x;
        s2 += x * x;
        ++n;
    }
    double mean() const { return n > 0 ? s1 / double(n) : 0; }
    double variance() const
    {
        return n > 1 ? std::fmax(0.0, (s2 - s1 * s1 / double(n)) / double(n - 1)) : 0;
    }
    /// The standard error of the mean, sigma / sqrt(n).
    double error() const { return n > 0 ? std::sqrt(variance() / double(n)) : 0; }
};

/// A material of grey albedo rho and grey emission le.
inline rt::material grey(float rho, float le = 0)
{
    rt::material m;
    m.name = "grey";
    m.kd = m.ka = rt::color(rho);
    m.emission = rt::color(le);
    return m;
}

/// The white furnace: a diffuse sphere of albedo `rho` (radius 1 at the
/// origin) in a uniform environment of radiance `env`, the background.
inline rt::scene furnace(float rho, float env)
{
    rt::scene s;
    s.materials.push_back(grey(rho));
    s.shapes.push_back(rt::sphere{rt::vec3(0), 1, 0});
    s.background = rt::color(env);
    return s;
}

/// The inside of a closed sphere (radius 1 at the origin) that emits `le`
/// everywhere and reflects with albedo `rho`: every ray inside it sees
/// Le / (1 - rho) (the sum Le + rho Le + rho^2 Le + ... of the bounces).
/// Glowing spheres are not sampled by next-event estimation (emitters.hpp).
inline rt::scene glowing_sphere(float rho, float le)
{
    rt::scene s;
    s.materials.push_back(grey(rho, le));
    s.shapes.push_back(rt::sphere{rt::vec3(0), 1, 0});
    return s;
}

/// The same with a closed cube of triangles (side 2 at the origin), glowing
/// towards the inside, which next-event estimation samples: Le / (1 - rho) again.
inline rt::scene glowing_cube(float rho, float le)
{
    rt::scene s;
    s.materials.push_back(grey(rho, le));
    rt::mesh box;
    for (int k = 0; k < 8; ++k)
        box.positions.push_back(rt::vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
    // two triangles per face, corners by their bits (x 1, y 2, z 4)
    const unsigned faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        box.triangles.push_back({f[0], f[1], f[2]});
        box.triangles.push_back({f[0], f[2], f[3]});
    }
    // each triangle's front (counter-clockwise side), where it glows from, faces the inside
    for (rt::index3& t : box.triangles) {
        const rt::vec3 a = box.positions[t[0]], b = box.positions[t[1]], c = box.positions[t[2]];
        if (glm::dot(glm::cross(b - a, c - a), a + b + c) > 0)
            std::swap(t[1], t[2]);
    }
    box.material = 0;
    s.shapes.push_back(box);
    return s;
}

/// A small Cornell-like box drawn in code: a room [-1, 1]^3 open at z = 1,
/// white floor, ceiling and back wall, a red left and a green right wall, a
/// square light of side 0.5 just below the ceiling, and a block on the floor.
inline rt::scene small_cornell()
{
    rt::scene s;
    s.materials = {grey(0.73f), grey(0.0f, 0.0f), grey(0.0f, 0.0f), grey(0.0f)};
    s.materials[1].kd = rt::color(0.65f, 0.06f, 0.05f);
    s.materials[2].kd = rt::color(0.12f, 0.45f, 0.09f);
    s.materials[3].kd = rt::color(0.78f);
    s.materials[3].emission = rt::color(12.0f, 10.0f, 8.0f);
    auto quad = [&](rt::vec3 a, rt::vec3 b, rt::vec3 c, rt::vec3 d, int material) {
        s.shapes.push_back(rt::triangle{a, b, c, material});
        s.shapes.push_back(rt::triangle{a, c, d, material});
    };
    using v = rt::vec3;
    quad(v(-1, -1, -1), v(1, -1, -1), v(1, -1, 1), v(-1, -1, 1), 0);  // floor
    quad(v(-1, 1, -1), v(1, 1, -1), v(1, 1, 1), v(-1, 1, 1), 0);      // ceiling
    quad(v(-1, -1, -1), v(1, -1, -1), v(1, 1, -1), v(-1, 1, -1), 0);  // back
    quad(v(-1, -1, -1), v(-1, 1, -1), v(-1, 1, 1), v(-1, -1, 1), 1);  // left, red
    quad(v(1, -1, -1), v(1, 1, -1), v(1, 1, 1), v(1, -1, 1), 2);      // right, green
    const float l = 0.25f, h = 0.99f;
    quad(v(-l, h, -l), v(l, h, -l), v(l, h, l), v(-l, h, l), 3);      // the light, its front facing down
    // a block 0.6 wide, 0.8 tall: its top and two faces that the camera sees
    quad(v(-0.6f, -0.2f, -0.6f), v(0, -0.2f, -0.6f), v(0, -0.2f, 0), v(-0.6f, -0.2f, 0), 0);
    quad(v(-0.6f, -1, 0), v(0, -1, 0), v(0, -0.2f, 0), v(-0.6f, -0.2f, 0), 0);
    quad(v(0, -1, -0.6f), v(0, -1, 0), v(0, -0.2f, 0), v(0, -0.2f, -0.6f), 0);
    s.background = rt::color(0.0f);
    return s;
}

/// The pinhole camera of small_cornell: from (0, 0, 3.5) towards -z, a
/// square film of n x n pixels that covers the room's opening.
struct pinhole {
    int n = 8;
    rt::ray operator()(rt::real x, rt::real y) const
    {
        const rt::real half = rt::real(0.33);
        const rt::real u = (x / rt::real(n) * 2 - 1) * half, v = (y / rt::real(n) * 2 - 1) * half;
        return rt::ray{rt::vec3(0, 0, rt::real(3.5)), rt::vec3(u, v, -1)};
    }
};

/// Radiance statistics (per channel the red one, or the luminance) of n paths
/// along `r`, each with its own generator seeded from (seed, k).
template <class Accelerator>
running paths_along(const rt::scene& s, const Accelerator& accel, const rt::emitter_list& lights, const rt::ray& r,
                    const rt::path_options& o, int n, std::uint64_t seed)
{
    running out;
    for (int k = 0; k < n; ++k) {
        rt::pcg32 rng = rt::seeded_generator(seed, 0, std::uint64_t(k) + 1, rt::integrator_stream);
        out.add(double(rt::path_radiance(s, accel, lights, r, rng, o).r));
    }
    return out;
}

/// "mean m (standard error e, n paths)", for messages.
inline std::string describe(const running& r)
{
    std::ostringstream out;
    out << r.mean() << " (standard error " << r.error() << ", " << r.n << " paths)";
    return out.str();
}

} // namespace path_scenes
