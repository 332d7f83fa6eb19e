// test_scenes.hpp - the geometry several suites build their cases from
// (stage 04 and the library's BVH and watertight suites): a tolerance and
// near(), a closed icosphere, the cube of tests/data, random scenes and rays,
// and the comparison of two hit records field by field.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <type_traits>
#include <utility>
#include <vector>

#include <rt/core/hit_record.hpp>
#include <rt/scene/mesh.hpp>
#include <rt/input/obj_loader.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/scene.hpp>
#include <rt/core/vec.hpp>

namespace rt_test {

using rt::real;
using rt::vec3;

inline constexpr bool in_float = std::is_same_v<real, float>;
inline const real tol = in_float ? real(1e-5) : real(1e-12);

inline bool near(real got, real want, real eps = tol)
{
    return std::fabs(got - want) <= eps * std::max(real(1), std::fabs(want));
}

inline bool near(const vec3& got, const vec3& want, real eps = tol)
{
    return near(got.x, want.x, eps) && near(got.y, want.y, eps) && near(got.z, want.z, eps);
}

// --- meshes built here ------------------------------------------------------

/// A unit icosahedron subdivided `levels` times (each triangle into four, the
/// new corners pushed onto the sphere), then scaled and moved. Corners shared
/// by neighbouring triangles are one index, so the mesh is closed; every face
/// is counter-clockwise seen from outside.
inline rt::mesh icosphere(int levels, const vec3& center, real radius)
{
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<std::array<double, 3>> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                            {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<rt::index3> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    auto unit = [](std::array<double, 3> v) {
        const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        return std::array<double, 3>{v[0] / l, v[1] / l, v[2] / l};
    };
    for (auto& v : p)
        v = unit(v);
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto found = middle.find(key);
            if (found != middle.end())
                return found->second;
            p.push_back(unit({p[a][0] + p[b][0], p[a][1] + p[b][1], p[a][2] + p[b][2]}));
            const auto index = std::uint32_t(p.size() - 1);
            middle[key] = index;
            return index;
        };
        std::vector<rt::index3> finer;
        for (const rt::index3& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.push_back({f[0], ab, ca});
            finer.push_back({f[1], bc, ab});
            finer.push_back({f[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        faces = finer;
    }
    rt::mesh m;
    for (const auto& v : p)
        m.positions.push_back(center + radius * vec3(real(v[0]), real(v[1]), real(v[2])));
    for (rt::index3 f : faces) { // make every face counter-clockwise seen from outside
        const vec3 a = m.positions[f[0]] - center, b = m.positions[f[1]] - center, c = m.positions[f[2]] - center;
        if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0)
            std::swap(f[1], f[2]);
        m.triangles.push_back(f);
    }
    return m;
}

inline rt::mesh cube_from_file()
{
    return rt::load_obj(RT_TEST_DATA_DIR "/cube.obj").geometry;
}

inline rt::scene scene_of(rt::mesh m)
{
    rt::scene s;
    s.shapes.emplace_back(std::move(m));
    return s;
}

/// A random scene: spheres, single triangles (some sharing edges, in a grid)
/// and meshes, as asked.
inline rt::scene random_scene(std::mt19937& random, int spheres, int triangles, bool meshes)
{
    std::uniform_real_distribution<real> pos(-5, 5), size(real(0.05), 1), unit(-1, 1);
    rt::scene s;
    for (int k = 0; k < spheres; ++k) {
        rt::sphere ball;
        ball.center = vec3{pos(random), pos(random), pos(random)};
        ball.radius = size(random);
        ball.material = k % 3;
        s.shapes.emplace_back(ball);
        if (k % 5 == 0 && triangles > 0) { // interleave kinds in the shape list
            const vec3 c{pos(random), pos(random), pos(random)};
            s.shapes.emplace_back(rt::triangle{c, c + vec3{unit(random), unit(random), unit(random)},
                                               c + vec3{unit(random), unit(random), unit(random)}, 1});
            --triangles;
        }
    }
    for (int k = 0; k < triangles; ++k) {
        if (k < 64) { // an 8 x 4 grid of squares as separate triangles, sharing edges and corners
            const real x = real(k % 8) - 4, y = real(k / 8) - 2;
            const vec3 p00(x, y, 0), p10(x + 1, y, 0), p01(x, y + 1, 0), p11(x + 1, y + 1, 0);
            s.shapes.emplace_back(k % 2 == 0 ? rt::triangle{p00, p10, p11, 2} : rt::triangle{p00, p11, p01, 2});
            continue;
        }
        const vec3 c{pos(random), pos(random), pos(random)};
        const real r = size(random);
        s.shapes.emplace_back(rt::triangle{c + r * vec3{unit(random), unit(random), unit(random)},
                                           c + r * vec3{unit(random), unit(random), unit(random)},
                                           c + r * vec3{unit(random), unit(random), unit(random)}, -1});
    }
    if (meshes) {
        s.shapes.emplace_back(icosphere(2, vec3(1, 1.5f, -2), real(1.2)));
        rt::mesh box = cube_from_file();
        for (vec3& p : box.positions)
            p = p * real(2) + vec3(-2, 1, 2);
        box.face_materials.assign(box.triangles.size(), 1);
        s.shapes.emplace_back(std::move(box));
    }
    return s;
}

/// Random rays through the scene's region, some with unit, some with long or
/// short directions, some axis-parallel (with -0) and some aimed at grid corners.
inline std::vector<rt::ray> random_rays(std::mt19937& random, int count)
{
    std::uniform_real_distribution<real> pos(-7, 7), unit(-1, 1);
    std::vector<rt::ray> rays;
    for (int k = 0; k < count; ++k) {
        rt::ray r;
        r.origin = vec3{pos(random), pos(random), pos(random)};
        switch (k % 5) {
        case 0:
            r.direction = glm::normalize(vec3{unit(random), unit(random), unit(random)});
            break;
        case 1:
            r.direction = vec3{unit(random), unit(random), unit(random)} * real(37);
            break;
        case 2: { // axis-parallel, any sign of zero
            const int axis = k % 3;
            r.direction = vec3(k % 7 < 3 ? real(0) : -real(0));
            r.direction[axis] = unit(random) < 0 ? -1 : 1;
            break;
        }
        case 3: { // at a corner of the grid
            const vec3 corner(real(k % 9) - 4, real(k % 5) - 2, 0);
            r.direction = corner - r.origin;
            break;
        }
        default:
            r.direction = vec3{unit(random), unit(random), unit(random)} * real(0.01);
        }
        if (glm::dot(r.direction, r.direction) == 0)
            r.direction = vec3(1, 0, 0);
        rays.push_back(r);
    }
    return rays;
}

inline bool same_hit(const rt::hit_record& a, const rt::hit_record& b)
{
    return a.t == b.t && a.shape == b.shape && a.primitive == b.primitive && a.material == b.material &&
           a.point == b.point && a.normal == b.normal && a.geometric_normal == b.geometric_normal &&
           a.front_face == b.front_face && a.b1 == b.b1 && a.b2 == b.b2 && a.point_error == b.point_error;
}


} // namespace rt_test
