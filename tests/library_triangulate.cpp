// library_triangulate.cpp - rt::triangulate_polygon (include/rt/input/triangulate.hpp):
// the robust orientation test, and the promise that every simple polygon,
// convex or concave, in any plane, gives n - 2 triangles inside it whose
// areas add up to its area.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include <rt/input/triangulate.hpp>

namespace {

using dvec2 = glm::dvec2;
using dvec3 = glm::dvec3;

// ---- the test's own geometry, in long double, independent of the header ----

long double cross2(const dvec2& a, const dvec2& b, const dvec2& c)
{
    return (static_cast<long double>(a.x) - c.x) * (static_cast<long double>(b.y) - c.y) -
           (static_cast<long double>(a.y) - c.y) * (static_cast<long double>(b.x) - c.x);
}

/// The area of a plane polygon by the shoelace formula (the surveyor's
/// formula; Newell's method restricted to a plane).
double shoelace_area(const std::vector<dvec2>& p)
{
    long double twice = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const dvec2& a = p[i];
        const dvec2& b = p[(i + 1) % p.size()];
        twice += static_cast<long double>(a.x) * b.y - static_cast<long double>(b.x) * a.y;
    }
    return double(std::fabs(twice) / 2);
}

/// Whether q is inside the polygon (crossing number, Jordan curve theorem).
bool inside_polygon(const std::vector<dvec2>& p, const dvec2& q)
{
    bool inside = false;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        if ((p[i].y > q.y) != (p[j].y > q.y)) {
            const long double x = p[j].x + (static_cast<long double>(q.y) - p[j].y) * (p[i].x - p[j].x) / (p[i].y - p[j].y);
            if (q.x < x)
                inside = !inside;
        }
    }
    return inside;
}

/// Whether segments (a, b) and (c, d) cross at a point inside both (touching
/// at an end, or running along each other, is not crossing).
bool segments_cross(const dvec2& a, const dvec2& b, const dvec2& c, const dvec2& d)
{
    const long double abc = cross2(a, b, c), abd = cross2(a, b, d), cda = cross2(c, d, a), cdb = cross2(c, d, b);
    return ((abc > 0 && abd < 0) || (abc < 0 && abd > 0)) && ((cda > 0 && cdb < 0) || (cda < 0 && cdb > 0));
}

/// A random plane: its origin and two orthonormal directions.
struct plane {
    dvec3 origin, e1, e2;
};

plane random_plane(std::mt19937& rng)
{
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> offset(-100.0, 100.0);
    dvec3 n;
    do {
        n.x = gauss(rng);
        n.y = gauss(rng);
        n.z = gauss(rng);
    } while (glm::length(n) < 1e-3);
    n = glm::normalize(n);
    const dvec3 helper = std::fabs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    plane result;
    result.e1 = glm::normalize(glm::cross(n, helper));
    result.e2 = glm::cross(n, result.e1);
    result.origin.x = offset(rng);
    result.origin.y = offset(rng);
    result.origin.z = offset(rng);
    return result;
}

std::vector<rt::vec3> place(const std::vector<dvec2>& polygon, const plane& where, double scale)
{
    std::vector<rt::vec3> corners;
    for (const dvec2& p : polygon) // the plane's offset grows with the polygon: rounding stays relative
        corners.push_back(rt::vec3(scale * (where.origin + p.x * where.e1 + p.y * where.e2)));
    return corners;
}

/// A star-shaped polygon about the origin: n distinct random angles and, for
/// `convex`, all radii 1 (corners on a circle: convex), else random radii.
std::vector<dvec2> star_polygon(std::mt19937& rng, std::size_t n, bool convex)
{
    std::uniform_real_distribution<double> angle(0.0, 2 * 3.14159265358979323846);
    std::uniform_real_distribution<double> radius(0.15, 1.0);
    std::vector<double> angles;
    while (angles.size() < n) {
        const double a = angle(rng);
        angles.push_back(a);
        std::sort(angles.begin(), angles.end());
        // keep the corners apart, so that rounding to float cannot touch them
        for (std::size_t i = 1; i < angles.size(); ++i)
            if (angles[i] - angles[i - 1] < 1e-3) {
                angles.erase(angles.begin() + long(i));
                break;
            }
    }
    // every angular gap below pi (the wrap-around one too): each edge then
    // turns less than half way about the origin, and the polygon is simple
    double largest_gap = 2 * 3.14159265358979323846 - (angles.back() - angles.front());
    for (std::size_t i = 1; i < angles.size(); ++i)
        largest_gap = std::max(largest_gap, angles[i] - angles[i - 1]);
    if (largest_gap >= 3.1)
        return star_polygon(rng, n, convex);
    std::vector<dvec2> polygon;
    for (const double a : angles) {
        const double r = convex ? 1.0 : radius(rng);
        polygon.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    return polygon;
}

/// The smallest distance of a corner from an edge it does not end.
double clearance(const std::vector<dvec2>& p)
{
    double smallest = 1e300;
    for (std::size_t k = 0; k < p.size(); ++k)
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::size_t j = (i + 1) % p.size();
            if (k == i || k == j)
                continue;
            const dvec2 edge = p[j] - p[i];
            const double t = std::clamp(glm::dot(p[k] - p[i], edge) / glm::dot(edge, edge), 0.0, 1.0);
            smallest = std::min(smallest, glm::length(p[k] - (p[i] + t * edge)));
        }
    return smallest;
}

/// A random simple polygon: random points joined in random order, then 2-opt
/// moves (reverse the path between two crossing edges) until no edges cross;
/// each move shortens the tour, so it ends (van Leeuwen and Schoone, 1981).
std::vector<dvec2> two_opt_polygon(std::mt19937& rng, std::size_t n)
{
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    for (;;) {
        std::vector<dvec2> p;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = coordinate(rng);
            const double y = coordinate(rng);
            p.emplace_back(x, y);
        }
        bool changed = true;
        while (changed) {
            changed = false;
            for (std::size_t i = 0; i < n && !changed; ++i)
                for (std::size_t j = i + 2; j < n && !changed; ++j) {
                    if (i == 0 && j == n - 1)
                        continue;
                    if (segments_cross(p[i], p[i + 1], p[j], p[(j + 1) % n])) {
                        std::reverse(p.begin() + long(i) + 1, p.begin() + long(j) + 1);
                        changed = true;
                    }
                }
        }
        if (clearance(p) > 1e-3) // well apart, so that rounding to float keeps it simple
            return p;
    }
}

/// Every promise for one simple polygon; `polygon` is its plane coordinates,
/// `corners` the same corners placed in 3-D. Returns the largest relative area error.
double check_triangulation(const std::vector<dvec2>& polygon, const std::vector<rt::vec3>& corners,
                           const std::string& what)
{
    CAPTURE(what);
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) // the test's polygons are simple, by the test's own check
        for (std::size_t j = i + 2; j < n; ++j)
            if (!(i == 0 && j == n - 1))
                REQUIRE_FALSE(segments_cross(polygon[i], polygon[i + 1], polygon[j], polygon[(j + 1) % n]));
    const rt::polygon_triangulation t = rt::triangulate_polygon(corners);
    if (t.problem != rt::polygon_problem::none) {
        std::string corners_text;
        for (const dvec2& p : polygon)
            corners_text += "(" + std::to_string(p.x) + " " + std::to_string(p.y) + ") ";
        CAPTURE(corners_text);
        CAPTURE(t.at[0]);
        CAPTURE(t.at[1]);
        REQUIRE(t.problem == rt::polygon_problem::none);
    }
    REQUIRE(t.triangles.size() == n - 2);
    // the area in the plane, and in 3-D (Newell's normal of the float corners)
    const double area = shoelace_area(polygon);
    long double winding = 0; // twice the signed area: > 0 counter-clockwise
    for (std::size_t i = 0; i < n; ++i)
        winding += static_cast<long double>(polygon[i].x) * polygon[(i + 1) % n].y -
                   static_cast<long double>(polygon[(i + 1) % n].x) * polygon[i].y;
    dvec3 newell(0.0); // relative to corner 0, so that the plane's distance from the origin cancels nothing
    for (std::size_t i = 1; i + 1 < n; ++i)
        newell += glm::cross(dvec3(corners[i]) - dvec3(corners[0]), dvec3(corners[i + 1]) - dvec3(corners[0]));
    double plane_sum = 0, space_sum = 0;
    for (const rt::corner3& tri : t.triangles) {
        REQUIRE(tri[0] < n);
        REQUIRE(tri[1] < n);
        REQUIRE(tri[2] < n);
        const dvec2& a = polygon[tri[0]];
        const dvec2& b = polygon[tri[1]];
        const dvec2& c = polygon[tri[2]];
        const long double signed_twice = cross2(a, b, c);
        // every triangle winds as the polygon does, and none is flat
        CHECK(signed_twice * winding > 0);
        plane_sum += double(std::fabs(signed_twice) / 2);
        const dvec3 A(corners[tri[0]]), B(corners[tri[1]]), C(corners[tri[2]]);
        const dvec3 normal = glm::cross(B - A, C - A);
        CHECK(glm::dot(normal, newell) > 0);
        space_sum += glm::length(normal) / 2;
        // inside: the centroid is, and no edge of the triangle crosses an edge of the polygon
        CHECK(inside_polygon(polygon, (a + b + c) / 3.0));
        const dvec2 tri_corners[3] = {a, b, c};
        for (int e = 0; e < 3; ++e)
            for (std::size_t i = 0; i < n; ++i)
                CHECK_FALSE(segments_cross(tri_corners[e], tri_corners[(e + 1) % 3], polygon[i], polygon[(i + 1) % n]));
    }
    const double plane_error = std::fabs(plane_sum - area) / area;
    const double space_error = std::fabs(space_sum - glm::length(newell) / 2) / (glm::length(newell) / 2);
    CHECK(plane_error < 1e-12);
    CHECK(space_error < 1e-6);
    return std::max(plane_error, space_error);
}

} // namespace

TEST_CASE("orient2d: exact signs where double arithmetic gets them wrong")
{
    // Points p = (0.5 + i u, 0.5 + j u), u = 2^-53 (one unit in the last place
    // at 0.5), against the line through q = (12, 12) and r = (24, 24):
    // orient(p, q, r) = (px - 24)(-12) - (py - 24)(-12) = 12 (py - px), whose
    // sign is the sign of j - i (Shewchuk 1997 shows the same experiment).
    const double u = std::ldexp(1.0, -53);
    const dvec2 q(12, 12), r(24, 24);
    int naive_wrong = 0, robust_wrong = 0, cases = 0;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j) {
            const dvec2 p(0.5 + i * u, 0.5 + j * u);
            const int truth = (j > i) - (j < i);
            naive_wrong += rt::detail::orient2d_naive(p, q, r) != truth;
            robust_wrong += rt::detail::orient2d(p, q, r) != truth;
            ++cases;
        }
    MESSAGE("orient2d near a line: double arithmetic wrong in " << naive_wrong << " of " << cases
                                                                << " cases, the adaptive test in " << robust_wrong);
    CHECK(naive_wrong > 0); // the plain method fails here...
    CHECK(robust_wrong == 0); // ...and the robust one does not
}

TEST_CASE("orient2d: exact expansions on coordinates of very different sizes")
{
    // (a - c) x (b - c) with a = (X, 1), b = (X + 2^50, 1 + 2^-52), c = (0, 0),
    // X = the double nearest 1e30 (a multiple of 2^47, so X + 2^50 is exact):
    // X (1 + 2^-52) - (X + 2^50) = X 2^-52 - 2^50, about 2.2e14 - 1.1e15 < 0,
    // while each product is about 1e30: its rounding error alone is 2^46.
    const double X = 1e30;
    const dvec2 a(X, 1), b(X + std::ldexp(1.0, 50), 1 + std::ldexp(1.0, -52)), c(0, 0);
    const double exact = X * std::ldexp(1.0, -52) - std::ldexp(1.0, 50); // both terms exact: the sign is
    CHECK(exact < 0);
    CHECK(rt::detail::orient2d(a, b, c) == -1);
    CHECK(rt::detail::orient2d_exact(a, b, c) == -1);
    CHECK(rt::detail::orient2d(a, a, c) == 0);
    CHECK(rt::detail::orient2d(c, a, b) == -1); // a cyclic shift keeps the sign
    CHECK(rt::detail::orient2d(b, a, c) == 1);  // a swap flips it
}

TEST_CASE("a concave quad is split at its reflex corner, not along its shorter diagonal")
{
    // the quad: v 0 0 0 / v 4 0.5 0 / v 0 1 0 / v 0.2 0.5 0 / f 1 2 3 4
    // shoelace: (0*0.5 - 4*0) + (4*1 - 0*0.5) + (0*0.5 - 0.2*1) + (0.2*0 - 0*0.5) = 3.8: area 1.9
    const std::vector<dvec2> quad = {{0, 0}, {4, 0.5}, {0, 1}, {0.2, 0.5}};
    const std::vector<rt::vec3> corners = {{0, 0, 0}, {4, 0.5f, 0}, {0, 1, 0}, {0.2f, 0.5f, 0}};
    CHECK(shoelace_area(quad) == doctest::Approx(1.9).epsilon(1e-12));
    // the shorter diagonal (corner 1 to 3, length 1) lies outside: its two
    // triangles cover 2 + 0.1 = 2.1, what rt gave before
    const double shorter = double(std::fabs(cross2(quad[0], quad[1], quad[2])) / 2 +
                                  std::fabs(cross2(quad[0], quad[2], quad[3])) / 2);
    CHECK(shorter == doctest::Approx(2.1).epsilon(1e-12));
    check_triangulation(quad, corners, "concave quad");
}

TEST_CASE("a convex quad keeps the diagonal whose triangles have the larger smallest angle")
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    int split_02 = 0, split_13 = 0;
    for (int k = 0; k < 500; ++k) {
        std::vector<dvec2> quad;
        for (int c = 0; c < 4; ++c) {
            const double angle = (c + 0.5 + jitter(rng)) * 3.14159265358979323846 / 2;
            const double rx = 1 + jitter(rng) * 2;
            quad.emplace_back(rx * std::cos(angle), std::sin(angle));
        }
        const std::vector<rt::vec3> corners = place(quad, random_plane(rng), 3.0);
        bool convex = true;
        for (int c = 0; c < 4; ++c)
            convex = convex && cross2(quad[c], quad[(c + 1) % 4], quad[(c + 2) % 4]) > 1e-3;
        if (!convex)
            continue;
        check_triangulation(quad, corners, "convex quad");
        const rt::polygon_triangulation t = rt::triangulate_polygon(corners);
        const auto smallest_angle = [&](int a, int b, int c) {
            const dvec3 p[3] = {dvec3(corners[a]), dvec3(corners[b]), dvec3(corners[c])};
            double least = 4;
            for (int i = 0; i < 3; ++i) {
                const dvec3 e1 = p[(i + 1) % 3] - p[i], e2 = p[(i + 2) % 3] - p[i];
                least = std::min(least, std::acos(glm::dot(e1, e2) / (glm::length(e1) * glm::length(e2))));
            }
            return least;
        };
        const double along_02 = std::min(smallest_angle(0, 1, 2), smallest_angle(0, 2, 3));
        const double along_13 = std::min(smallest_angle(0, 1, 3), smallest_angle(1, 2, 3));
        bool uses_02 = false;
        for (const rt::corner3& tri : t.triangles)
            uses_02 = uses_02 || (std::count(tri.begin(), tri.end(), 0u) && std::count(tri.begin(), tri.end(), 2u) &&
                                  std::count(tri.begin(), tri.end(), 1u));
        CHECK(std::min(along_02, along_13) <= (uses_02 ? along_02 : along_13) + 1e-9);
        (uses_02 ? split_02 : split_13) += 1;
    }
    MESSAGE("convex quads: " << split_02 << " split along 0-2, " << split_13 << " along 1-3");
    CHECK(split_02 > 0); // both diagonals occur: the rule chooses
    CHECK(split_13 > 0);
}

TEST_CASE("a concave heptagon gives 5 triangles covering its area")
{
    // a comb: two teeth up from a base, corners counter-clockwise
    const std::vector<dvec2> heptagon = {{0, 0}, {4, 0}, {4, 3}, {3, 3}, {2, 1}, {1, 3}, {0, 3}};
    // area: the 4 x 3 rectangle less the notch triangle (3,3) (2,1) (1,3) of area 2 * 2 / 2 = 2
    CHECK(shoelace_area(heptagon) == doctest::Approx(10.0).epsilon(1e-12));
    std::vector<rt::vec3> corners;
    for (const dvec2& p : heptagon)
        corners.emplace_back(rt::real(p.x), rt::real(0), rt::real(p.y)); // in the xz plane
    check_triangulation(heptagon, corners, "heptagon");
}

TEST_CASE("a ring written as one polygon with a slit gives 64 triangles covering the ring")
{
    // as exporters write a face with a hole: the outer circle (32 corners,
    // counter-clockwise), back to its first corner, along the slit to the
    // inner circle, around it clockwise, back along the slit: 66 corners
    const double pi = 3.14159265358979323846;
    const int segments = 32;
    std::vector<dvec2> ring;
    for (int k = 0; k < segments; ++k)
        ring.emplace_back(2 * std::cos(2 * pi * k / segments), 2 * std::sin(2 * pi * k / segments));
    ring.push_back(ring.front());
    for (int k = 0; k <= segments; ++k)
        ring.emplace_back(std::cos(-2 * pi * k / segments), std::sin(-2 * pi * k / segments));
    REQUIRE(ring.size() == 66);
    // the rounded corners must be the same points where the file repeats them
    std::vector<rt::vec3> corners;
    for (const dvec2& p : ring)
        corners.emplace_back(rt::real(p.x), rt::real(p.y), rt::real(0));
    std::vector<dvec2> rounded;
    for (const rt::vec3& c : corners)
        rounded.emplace_back(double(c.x), double(c.y));
    // the ring's area: two regular 32-gons, (1/2) n r^2 sin(2 pi / n) each
    const double expected = 0.5 * segments * std::sin(2 * pi / segments) * (4 - 1);
    CHECK(shoelace_area(rounded) == doctest::Approx(expected).epsilon(1e-6));
    const rt::polygon_triangulation t = rt::triangulate_polygon(corners);
    REQUIRE(t.problem == rt::polygon_problem::none);
    CHECK(t.triangles.size() == 64);
    double sum = 0;
    for (const rt::corner3& tri : t.triangles) {
        const long double twice = cross2(rounded[tri[0]], rounded[tri[1]], rounded[tri[2]]);
        CHECK(twice > 0);
        sum += double(twice / 2);
        // nothing inside the hole: the centroid is at least the inner radius from the centre
        const dvec2 centroid = (rounded[tri[0]] + rounded[tri[1]] + rounded[tri[2]]) / 3.0;
        CHECK(glm::length(centroid) > std::cos(pi / segments) - 1e-6);
    }
    MESSAGE("ring of 66 corners: " << t.triangles.size() << " triangles, area " << sum << " of " << expected);
    CHECK(sum == doctest::Approx(shoelace_area(rounded)).epsilon(1e-12));
}

TEST_CASE("300 random simple 5- to 9-gons are all triangulated right")
{
    std::mt19937 rng(15);
    std::uniform_int_distribution<int> corners_of(5, 9);
    double worst = 0;
    int tinyobj_wrong = 0;
    for (int k = 0; k < 300; ++k) {
        const std::size_t n = std::size_t(corners_of(rng));
        const std::vector<dvec2> polygon = k % 2 ? star_polygon(rng, n, false) : two_opt_polygon(rng, n);
        worst = std::max(worst, check_triangulation(polygon, place(polygon, random_plane(rng), 5.0), "small polygon"));
        // the same polygon (in the z = 0 plane) through tinyobjloader's own
        // triangulation, which rt used before: right when it gives n - 2
        // triangles whose areas add up to the polygon's
        std::string obj;
        for (const dvec2& p : polygon)
            obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " 0\n";
        obj += "f";
        for (std::size_t i = 1; i <= n; ++i)
            obj += " " + std::to_string(i);
        obj += "\n";
        std::istringstream in(obj);
        tinyobj::attrib_t attrib;
        std::vector<tinyobj::shape_t> shapes;
        std::vector<tinyobj::material_t> materials;
        std::string warning, failure;
        tinyobj::MaterialStreamReader no_materials(in);
        REQUIRE(tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &failure, &in, &no_materials, true));
        std::vector<dvec2> read; // the corners as tinyobjloader read them
        for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
            read.emplace_back(attrib.vertices[i], attrib.vertices[i + 1]);
        double sum = 0;
        std::size_t triangles = 0;
        for (const tinyobj::shape_t& shape : shapes)
            for (std::size_t t = 0; t + 2 < shape.mesh.indices.size(); t += 3, ++triangles)
                sum += double(std::fabs(cross2(read[std::size_t(shape.mesh.indices[t].vertex_index)],
                                               read[std::size_t(shape.mesh.indices[t + 1].vertex_index)],
                                               read[std::size_t(shape.mesh.indices[t + 2].vertex_index)])) / 2);
        const double area = shoelace_area(read);
        tinyobj_wrong += triangles != n - 2 || std::fabs(sum - area) > 1e-6 * area;
    }
    MESSAGE("300 random simple 5- to 9-gons: rt right in all, largest relative area error "
            << worst << "; tinyobjloader's triangulation wrong in " << tinyobj_wrong);
    CHECK(tinyobj_wrong > 0); // the method rt used before fails here
}

TEST_CASE("random simple polygons of 4 to 64 corners in random planes keep n - 2 triangles, area and containment")
{
    std::mt19937 rng(2026);
    std::uniform_int_distribution<int> corners_of(4, 64);
    std::uniform_real_distribution<double> log_scale(-3.0, 3.0);
    double worst = 0;
    int polygons = 0;
    for (int k = 0; k < 600; ++k) {
        const std::size_t n = std::size_t(corners_of(rng));
        const int kind = k % 3; // convex star, concave star, 2-opt
        const std::vector<dvec2> polygon =
            kind == 2 ? two_opt_polygon(rng, n) : star_polygon(rng, n, kind == 0);
        const double scale = std::pow(10.0, log_scale(rng));
        worst = std::max(worst, check_triangulation(polygon, place(polygon, random_plane(rng), scale),
                                                    kind == 0 ? "convex" : kind == 1 ? "star" : "2-opt"));
        ++polygons;
    }
    MESSAGE(polygons << " random simple polygons of 4 to 64 corners: largest relative area error " << worst);
}

TEST_CASE("a corner on the line between its neighbours is fine")
{
    const std::vector<dvec2> square = {{0, 0}, {1, 0}, {2, 0}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
    std::vector<rt::vec3> corners;
    for (const dvec2& p : square)
        corners.emplace_back(rt::real(p.y), rt::real(p.x), rt::real(1)); // mirrored: clockwise about +z
    check_triangulation(square, corners, "collinear corners");
}

TEST_CASE("polygons that are not simple are named, with the fan as the fallback")
{
    const auto problem_of = [](const std::vector<rt::vec3>& corners) {
        return rt::triangulate_polygon(corners).problem;
    };
    // bow ties: edges 0-1 and 2-3 cross; the second one's lobes cancel (Newell normal 0)
    const rt::polygon_triangulation bow = rt::triangulate_polygon({{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 1, 0}});
    CHECK(bow.problem == rt::polygon_problem::not_simple);
    CHECK(bow.triangles.size() == 2);
    CHECK(problem_of({{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}}) == rt::polygon_problem::not_simple);
    // a corner repeated next to itself
    CHECK(problem_of({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}}) == rt::polygon_problem::repeated_corner);
    CHECK(problem_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}}) == rt::polygon_problem::repeated_corner);
    // every corner on one line
    CHECK(problem_of({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}) == rt::polygon_problem::no_area);
    // a corner inside another edge (the polygon touches itself)
    CHECK(problem_of({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 0, 0}, {0, 2, 0}}) == rt::polygon_problem::not_simple);
    // a pentagram, its edges crossing five times
    std::vector<rt::vec3> star;
    for (int k = 0; k < 5; ++k)
        star.emplace_back(rt::real(std::cos(k * 4 * 3.14159265358979323846 / 5)),
                          rt::real(std::sin(k * 4 * 3.14159265358979323846 / 5)), rt::real(0));
    CHECK(problem_of(star) == rt::polygon_problem::not_simple);
    CHECK(problem_of({{0, 0, 0}, {1, 0, 0}}) == rt::polygon_problem::too_few_corners);
}
