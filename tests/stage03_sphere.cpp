// Stage 03 - ray-sphere intersection: the textbook quadratic (the exercise) and
// the stable method of Ray Tracing Gems ch. 7 (the library default).
//
// Two kinds of test:
//  - the accuracy table: a unit sphere at distances 1e1 ... 1e6 and a large
//    "ground" sphere seen from just above it, each root compared with the
//    exact root (a closed form, or the same quadratic evaluated in long double
//    from the same float inputs, whose error is far below one ulp of real).
//    The stable method stays within 4 ulps everywhere; the textbook's error
//    passes that bound, and in float, far away, it misses rays that hit and
//    hits rays that miss. The
//    table is printed (doctest MESSAGE) and copied into docs/stages/03-sphere.md.
//  - properties: hit points on the sphere, inside and tangent rays, rays
//    pointing away, the [tmin, tmax] interval, normals, materials, and the two
//    methods agreeing where the textbook is accurate.
// Only stage-03 code is called: rays and spheres are built here, not loaded.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <rt/hit_record.hpp>
#include <rt/ray.hpp>
#include <rt/sphere.hpp>
#include <rt/sphere_stable.hpp>

namespace {

using rt::real;
using wide = long double;

/// The accuracy bound of the stable method, in units in the last place of t.
constexpr double ulp_bound = 4;
const real infinity = std::numeric_limits<real>::infinity();

using hit_function = bool (*)(const rt::sphere&, const rt::ray&, real, real, rt::hit_record&);
struct method {
    const char* name;
    hit_function hit;
};
const method textbook{"textbook", rt::hit_sphere_textbook};
const method stable{"stable", rt::hit_sphere};
const method both_methods[] = {textbook, stable};

/// One unit in the last place of real at |x| (the gap to the next larger real).
wide ulp_at(wide x)
{
    const real magnitude = real(std::fabs(x));
    return wide(std::nextafter(magnitude, infinity)) - wide(magnitude);
}

/// |got - exact| in ulps of real at the exact value.
double error_ulps(real got, wide exact)
{
    return double(std::fabs(wide(got) - exact) / ulp_at(exact));
}


real next_up(real x) { return std::nextafter(x, infinity); }
real next_down(real x) { return std::nextafter(x, -infinity); }

/// A unit sphere at distance D down the -z axis, and a ray along -z from
/// (h, 0, 0): it passes at distance h from the centre, so (FCG sec. 4.4.1 with
/// |d| = 1) its nearest root is exactly t = D - sqrt(1 - h^2).
struct axis_case {
    rt::sphere s;
    rt::ray r;
    wide exact;
};

/// Uniform reals in [0, 1) from the raw 32-bit output of std::mt19937, which
/// the standard fixes for a given seed (its distributions are not portable).
/// Each draw is its own statement: the order in which a compiler evaluates
/// the arguments of one call is unspecified (g++ and clang++ differ).
class portable_random {
public:
    explicit portable_random(std::uint32_t seed) : engine_(seed) {}
    real uniform() { return real(engine_() >> 8) * real(1.0 / 16777216.0); }
    real between(real low, real high) { return low + (high - low) * uniform(); }
    rt::vec3 in_box(real half_side)
    {
        const real x = between(-half_side, half_side);
        const real y = between(-half_side, half_side);
        const real z = between(-half_side, half_side);
        return rt::vec3(x, y, z);
    }
    rt::vec3 unit_vector()
    {
        for (;;) {
            const rt::vec3 v = in_box(1);
            const real length2 = glm::dot(v, v);
            if (length2 > real(0.01) && length2 <= 1)
                return v / std::sqrt(length2);
        }
    }

private:
    std::mt19937 engine_;
};

/// Two unit vectors w, v with (u, w, v) orthonormal.
void perpendiculars(const rt::vec3& u, rt::vec3& w, rt::vec3& v)
{
    const rt::vec3 axis = std::fabs(u.x) < real(0.5) ? rt::vec3(1, 0, 0) : rt::vec3(0, 1, 0);
    w = glm::normalize(glm::cross(u, axis));
    v = glm::cross(u, w);
}

/// What one method did with one ray.
struct outcome {
    bool hit = false;
    double ulps = 0; ///< error of t in ulps at the exact root (when hit)
    wide depth_error = 0; ///< |t - exact| |d| / R (when hit)
};

/// The worst of a set of outcomes of one method, for rays that hit; or the
/// number of false hits, for rays that miss.
struct summary {
    int rays = 0;
    int misses = 0;
    int false_hits = 0;
    double worst_ulps = 0;
    wide worst_depth_error = 0;
    void add(const outcome& o)
    {
        ++rays;
        if (!o.hit) {
            ++misses;
        } else {
            worst_ulps = std::max(worst_ulps, o.ulps);
            worst_depth_error = std::max(worst_depth_error, o.depth_error);
        }
    }
};


/// One row of the distance table.
struct distance_row {
    real D = 0;
    outcome centred[2], off_centre[2], grazing[2]; // [textbook, stable]
    summary fan[2];      // rays that hit
    summary miss_fan[2]; // rays that pass at 1.1 R to 2 R from the centre
};

/// A sphere of radius R centred at (0, -R, 0), its top at the origin, and a
/// ray from height h above the top, going down and sideways: d = (0.75, -1, 0).
/// All inputs have few bits, so the long-double quadratic is exact to its last
/// rounding (f = (0, R + h, 0), c = h (2R + h)).
struct ground_row {
    real R = 0, h = 0;
    wide exact = 0;
    outcome result[2];
    outcome chapter; // the chapter's method with c in real
};

} // namespace

// ---------------------------------------------------------------------------
// Properties, each for both methods.

TEST_CASE("closed-form hits: unit sphere at distance 5, t = 4 for |d| = 1, 2 for |d| = 2, 8 for |d| = 1/2")
{
    for (const method& m : both_methods) {
        const std::string method_name = m.name; // a std::string: doctest prints a char* as a pointer
        CAPTURE(method_name);
        rt::sphere s;
        s.center = rt::vec3(0, 0, -5);
        for (real scale : {real(1), real(2), real(0.5)}) {
            CAPTURE(double(scale));
            const rt::ray r{rt::vec3(0), rt::vec3(0, 0, -scale)};
            rt::hit_record rec;
            INFO("the ray from the origin along -z meets the sphere at t = " << 4 / double(scale) << " (entering) and t = "
                 << 6 / double(scale) << " (leaving): expected the nearer root, t = " << 4 / double(scale));
            REQUIRE_MESSAGE(m.hit(s, r, 0, infinity, rec), "expected a hit: the ray points at the sphere's centre");
            CHECK(rec.t == real(4) / scale); // every step is exact for these inputs
            CHECK(rec.point == rt::vec3(0, 0, -4));
            CHECK(rec.normal == rt::vec3(0, 0, 1));
            CHECK(rec.geometric_normal == rt::vec3(0, 0, 1));
            CHECK(rec.front_face);
        }
        // passing 0.6 R from the centre: t = 5 - sqrt(1 - 0.36) = 4.2, normal (0.6, 0, 0.8)
        const rt::ray off{rt::vec3(real(0.6), 0, 0), rt::vec3(0, 0, -1)};
        rt::hit_record rec;
        REQUIRE_MESSAGE(m.hit(s, off, 0, infinity, rec), "expected a hit: the ray passes 0.6 R from the centre");
        const wide exact = 5 - std::sqrt(1 - wide(real(0.6)) * wide(real(0.6)));
        // the nearer root first, so that a far root is named as such before any accuracy check
        CHECK_MESSAGE(rec.t < real(5), "expected the nearer root t = 4.2, not the far one t = 5.8");
        INFO("t = " << double(rec.t) << " against the exact 4.2000000...: expected within 4 ulps");
        CHECK(error_ulps(rec.t, exact) <= ulp_bound);
        CHECK(rec.normal.x == doctest::Approx(0.6).epsilon(1e-6));
        CHECK(rec.normal.z == doctest::Approx(0.8).epsilon(1e-6));
    }
}

TEST_CASE("a ray starting inside hits the far side, with the back face flagged and the normal facing the ray")
{
    portable_random random(3);
    for (const method& m : both_methods) {
        const std::string method_name = m.name;
        CAPTURE(method_name);
        // from the centre: t = R / |d| exactly in the quadratic's terms
        rt::sphere s;
        s.center = rt::vec3(1, 2, 3);
        s.radius = 2;
        const rt::ray from_centre{s.center, rt::vec3(0, real(0.5), 0)};
        rt::hit_record rec;
        REQUIRE(m.hit(s, from_centre, 0, infinity, rec));
        CHECK(rec.t == real(4));
        CHECK(rec.point == rt::vec3(1, 4, 3));
        CHECK_FALSE_MESSAGE(rec.front_face, "expected front_face = false: the ray starts inside and leaves through the back face");
        CHECK(rec.normal == rt::vec3(0, -1, 0)); // the inward normal: it faces the ray
        // from random points inside, in random directions
        for (int k = 0; k < 200; ++k) {
            const rt::vec3 towards = random.unit_vector();
            const rt::vec3 origin = s.center + towards * (s.radius * real(0.95) * random.uniform());
            const rt::vec3 direction = random.unit_vector();
            const rt::ray r{origin, direction * random.between(real(0.5), real(2))};
            CAPTURE(k);
            REQUIRE(m.hit(s, r, 0, infinity, rec));
            CHECK(rec.t > 0);
            CHECK_FALSE_MESSAGE(rec.front_face, "expected front_face = false: the ray starts inside the sphere");
            CHECK(glm::dot(rec.normal, r.direction) < 0);
            CHECK(glm::dot(rec.normal, rec.point - s.center) < 0); // the inward normal
            // and it is the only root ahead: nothing further along the ray
            rt::hit_record beyond;
            CHECK_FALSE_MESSAGE(m.hit(s, r, rec.t * real(1.001), infinity, beyond),
                                "expected no second hit beyond t = " << double(rec.t) << ": a ray from inside has one root ahead");
        }
    }
}

TEST_CASE("a tangent ray touches at one point with the normal perpendicular to it, one ulp further out misses")
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    for (const method& m : both_methods) {
        const std::string method_name = m.name;
        CAPTURE(method_name);
        const rt::ray tangent{rt::vec3(1, 0, 0), rt::vec3(0, 0, -1)};
        rt::hit_record rec;
        REQUIRE(m.hit(s, tangent, 0, infinity, rec));
        CHECK(rec.t == real(5)); // the double root
        CHECK(rec.point == rt::vec3(1, 0, -5));
        CHECK(rec.normal == rt::vec3(1, 0, 0));
        CHECK(glm::dot(rec.normal, tangent.direction) == 0);
        CHECK(rec.front_face); // a tangent ray counts as hitting the outside
        const rt::ray outside{rt::vec3(1 + real(1) / 1024, 0, 0), rt::vec3(0, 0, -1)};
        CHECK_FALSE_MESSAGE(m.hit(s, outside, 0, infinity, rec),
                            "expected a miss: the ray passes 1/1024 outside the sphere's silhouette");
    }
    // One ulp outside the silhouette either answer is fair to ask of the textbook
    // formula (its discriminant loses those 2 ulps next to 25): the contrast with
    // the stable method is in library_sphere_stable.cpp, on a copy of the formula.
}

TEST_CASE("rays pointing away from the sphere miss, the roots behind are found only when tmin allows")
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    for (const method& m : both_methods) {
        const std::string method_name = m.name;
        CAPTURE(method_name);
        const rt::ray away{rt::vec3(0), rt::vec3(0, 0, 1)}; // roots at -6 and -4
        rt::hit_record rec;
        CHECK_FALSE_MESSAGE(m.hit(s, away, 0, infinity, rec), "expected a miss: both roots (-6, -4) are behind the origin, tmin = 0");
        REQUIRE(m.hit(s, away, -100, infinity, rec)); // the whole line: the nearest root in the interval
        CHECK(rec.t == real(-6));
        CHECK(rec.front_face); // seen from behind its origin the ray still enters at -6
        const rt::ray beside{rt::vec3(0, 3, 0), rt::vec3(0, 0, -1)}; // passes 3 R from the centre
        CHECK_FALSE_MESSAGE(m.hit(s, beside, -100, infinity, rec), "expected a miss: the line passes 3 R from the centre");
    }
}

TEST_CASE("tmin and tmax are respected: roots 4 and 6, and intervals just around them")
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const rt::ray r{rt::vec3(0), rt::vec3(0, 0, -1)};
    struct interval_case {
        real tmin, tmax;
        bool hit;
        real t;
    };
    const interval_case cases[] = {
        {0, infinity, true, 4},
        {0, 4, true, 4},                            // the interval is closed
        {0, next_down(4), false, 0},                // the hit just beyond tmax is rejected
        {4, 4, true, 4},
        {next_up(4), infinity, true, 6},            // the first root below tmin: the second is returned
        {next_up(4), 6, true, 6},
        {next_up(4), next_down(6), false, 0},       // between the roots
        {real(4.5), real(5.5), false, 0},
        {next_up(6), infinity, false, 0},           // both roots below tmin
        {-infinity, infinity, true, 4},
    };
    for (const method& m : both_methods)
        for (const interval_case& k : cases) {
            const std::string method_name = m.name;
            CAPTURE(method_name);
            CAPTURE(double(k.tmin));
            CAPTURE(double(k.tmax));
            rt::hit_record rec;
            INFO("roots t = 4 and t = 6: expected " << (k.hit ? "a hit at t = " + std::to_string(int(k.t)) : std::string("a miss"))
                 << " for tmin <= t <= tmax (both ends included)");
            REQUIRE(m.hit(s, r, k.tmin, k.tmax, rec) == k.hit);
            if (k.hit)
                CHECK(rec.t == k.t);
        }
}

TEST_CASE("random rays at near spheres: the hit point is on the sphere, the normal unit and facing the ray")
{
    // Bounds in ulps of the largest magnitude involved (origin, point, centre,
    // radius): p = o + t d carries the error of t (<= 4 ulps for the stable
    // method) plus two roundings. The textbook's t is off by up to about 40
    // ulps at these distances (see the table), so its bound is looser; its
    // normal (p - c) / R inherits the point's error, the stable one is
    // normalised.
    portable_random random(11);
    struct bounds {
        double on_sphere, unit_normal;
    };
    const bounds textbook_bounds{64, 256}, stable_bounds{6, 2};
    bounds worst[2] = {{0, 0}, {0, 0}};
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
        rt::sphere s;
        s.center = random.in_box(5);
        s.radius = random.between(real(0.25), 3);
        s.material = k % 5;
        const rt::vec3 from = random.unit_vector();
        const rt::vec3 origin = s.center + from * (s.radius * random.between(real(1.5), 10));
        const rt::vec3 towards = random.unit_vector();
        const rt::vec3 aim = s.center + towards * (s.radius * random.between(0, real(1.2)));
        const rt::ray r{origin, (aim - origin) * random.between(real(0.1), 4)};
        for (const method& m : both_methods) {
            const std::string method_name = m.name;
            CAPTURE(method_name);
            CAPTURE(k);
            rt::hit_record rec;
            if (!m.hit(s, r, 0, infinity, rec))
                continue;
            ++hits;
            const bounds& bound = &m == &both_methods[0] ? textbook_bounds : stable_bounds;
            auto largest = [](const rt::vec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); };
            const real scale = std::max({largest(r.origin), largest(rec.point), largest(s.center), s.radius});
            const wide distance = std::sqrt(std::pow(wide(rec.point.x) - s.center.x, 2) +
                                            std::pow(wide(rec.point.y) - s.center.y, 2) +
                                            std::pow(wide(rec.point.z) - s.center.z, 2));
            const double off_sphere = double(std::fabs(distance - s.radius) / ulp_at(scale));
            CHECK(off_sphere <= bound.on_sphere);
            const wide normal_length = std::sqrt(wide(rec.normal.x) * rec.normal.x + wide(rec.normal.y) * rec.normal.y +
                                                 wide(rec.normal.z) * rec.normal.z);
            const double off_unit = double(std::fabs(normal_length - 1) / ulp_at(1));
            CHECK(off_unit <= bound.unit_normal);
            bounds& seen = worst[&m == &both_methods[0] ? 0 : 1];
            seen.on_sphere = std::max(seen.on_sphere, off_sphere);
            seen.unit_normal = std::max(seen.unit_normal, off_unit);
            CHECK(glm::dot(rec.normal, r.direction) <= 0); // faces the ray
            CHECK(rec.geometric_normal == rec.normal);     // a sphere has no separate shading normal
            CHECK(rec.front_face);                         // every origin is outside
            CHECK(glm::dot(rec.normal, rec.point - s.center) > 0);
            CHECK(rec.material == s.material);
            CHECK(rec.t > 0);
        }
    }
    CHECK(hits > 2000); // most rays are aimed inside the silhouette
    MESSAGE("worst in ulps: point off the sphere: textbook " << worst[0].on_sphere << ", stable " << worst[1].on_sphere
                                                              << "; normal length off 1: textbook " << worst[0].unit_normal
                                                              << ", stable " << worst[1].unit_normal << " (" << hits
                                                              << " hits)");
}

TEST_CASE("the material index is copied, barycentrics and primitive are zero, a miss leaves the record untouched")
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    for (const method& m : both_methods) {
        const std::string method_name = m.name;
        CAPTURE(method_name);
        for (int material : {7, 0, -1}) {
            s.material = material;
            rt::hit_record rec;
            rec.primitive = 99;
            rec.b1 = rec.b2 = real(0.5);
            REQUIRE(m.hit(s, rt::ray{rt::vec3(0), rt::vec3(0, 0, -1)}, 0, infinity, rec));
            CHECK(rec.material == material);
            CHECK(rec.primitive == 0);
            CHECK(rec.b1 == 0);
            CHECK(rec.b2 == 0);
        }
        rt::hit_record sentinel;
        sentinel.t = 123;
        sentinel.point = rt::vec3(1, 2, 3);
        sentinel.normal = sentinel.geometric_normal = rt::vec3(0, 1, 0);
        sentinel.front_face = false;
        sentinel.material = 42;
        sentinel.shape = 17;
        sentinel.primitive = 5;
        sentinel.b1 = real(0.25);
        sentinel.b2 = real(0.5);
        rt::hit_record rec = sentinel;
        CHECK_FALSE_MESSAGE(m.hit(s, rt::ray{rt::vec3(0, 3, 0), rt::vec3(0, 0, -1)}, 0, infinity, rec), "expected a miss: the line passes 3 R from the centre");
        CHECK_FALSE_MESSAGE(m.hit(s, rt::ray{rt::vec3(0), rt::vec3(0, 0, -1)}, 0, 1, rec), "expected a miss: the roots 4 and 6 are beyond tmax = 1");
        CHECK(rec.t == sentinel.t);
        CHECK(rec.point == sentinel.point);
        CHECK(rec.normal == sentinel.normal);
        CHECK(rec.geometric_normal == sentinel.geometric_normal);
        CHECK(rec.front_face == sentinel.front_face);
        CHECK(rec.material == sentinel.material);
        CHECK(rec.shape == sentinel.shape);
        CHECK(rec.primitive == sentinel.primitive);
        CHECK(rec.b1 == sentinel.b1);
        CHECK(rec.b2 == sentinel.b2);
    }
}

TEST_CASE("a degenerate ray (d = 0) misses, whether its origin is outside, inside or on the sphere")
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    for (const method& m : both_methods)
        for (const rt::vec3& origin : {rt::vec3(0), rt::vec3(0, 0, -5), rt::vec3(0, 0, -4)}) {
            const std::string method_name = m.name;
            CAPTURE(method_name);
            rt::hit_record rec;
            CHECK_FALSE_MESSAGE(m.hit(s, rt::ray{origin, rt::vec3(0)}, 0, infinity, rec), "expected a miss for a ray whose direction is (0, 0, 0)");
        }
}

TEST_CASE("where the textbook is accurate the two methods agree: near spheres, random rays (fixed seed)")
{
    // Spheres 2 to 10 radii away; rays aimed within 0.9 R of the centre (hits)
    // or between 1.1 R and 2 R (misses, clear of the silhouette). At these
    // distances the textbook's t is within 40 ulps (table, distance 1e1), so
    // 64 ulps of agreement is a real test of the same root, not a loose one.
    portable_random random(2024);
    int hits = 0, misses = 0;
    for (int k = 0; k < 3000; ++k) {
        rt::sphere s;
        s.center = random.in_box(3);
        s.radius = random.between(real(0.5), 2);
        const rt::vec3 u = random.unit_vector();
        rt::vec3 w, v;
        perpendiculars(u, w, v);
        const bool aim_inside = k % 3 != 0;
        const real reach = aim_inside ? real(0.9) * std::sqrt(random.uniform()) : random.between(real(1.1), 2);
        const real phi = real(6.283185307179586) * random.uniform();
        const rt::vec3 offset = reach * s.radius * (std::cos(phi) * w + std::sin(phi) * v);
        const real distance = s.radius * random.between(2, 10);
        const rt::ray r{s.center - u * distance + offset, u * random.between(real(0.25), 4)};
        rt::hit_record a, b;
        const bool hit_a = rt::hit_sphere_textbook(s, r, 0, infinity, a);
        const bool hit_b = rt::hit_sphere(s, r, 0, infinity, b);
        CAPTURE(k);
        REQUIRE(hit_a == aim_inside);
        REQUIRE(hit_b == aim_inside);
        if (!aim_inside) {
            ++misses;
            continue;
        }
        ++hits;
        CHECK(error_ulps(a.t, wide(b.t)) <= 64);
        CHECK(a.front_face == b.front_face);
        CHECK(glm::dot(a.normal, b.normal) > real(0.9999));
    }
    CHECK(hits == 2000);
    CHECK(misses == 1000);
}
