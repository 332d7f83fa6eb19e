// sphere_accuracy.hpp - the measurements of ray-sphere accuracy that
// tests/library_sphere_stable.cpp asserts and prints, tests/stage03_sphere.cpp
// uses as its exact reference, and tests/docs_figures.cpp quotes in
// docs/stages/03-going-further.md: one copy of the code, so the page, the
// printed table and the assertions cannot disagree.
//
// The accuracy table: a unit sphere at distances 1e1 ... 1e6 and a large
// "ground" sphere seen from just above it, each root compared with the exact
// root (a closed form, or the same quadratic evaluated in long double from the
// same float inputs, whose error is far below one ulp of real).
//
// The textbook method measured here is the stage-03 exercise itself,
// rt::hit_sphere_textbook (include/rt/intersection/sphere.hpp), whose reference body is the
// textbook formula: no copy of the answer sits outside its exercise region. In
// a kit where it is not written yet the tables measure the stable method alone
// (textbook_not_done); what is asserted about the textbook's side, and where,
// is in tests/textbook_methods.hpp. No doctest here (docs_figures is a plain
// program).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <rt/core/hit_record.hpp>
#include <rt/core/error.hpp>
#include <rt/core/ray.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/scene/sphere_shape.hpp>
#include <rt/intersection/sphere_stable.hpp>
#include <rt/core/vec.hpp>

#include "textbook_methods.hpp"

namespace rt_test {

using rt::real;
using wide = long double;

inline constexpr bool real_is_float = std::is_same<real, float>::value;
/// The accuracy bound of the stable method, in units in the last place of t.
inline constexpr double ulp_bound = 4;
inline const real infinity = std::numeric_limits<real>::infinity();

/// Whether long double is wide enough to serve as "exact" for rt::real: it
/// must carry at least 10 more bits (float: always; double: x87 long double).
inline constexpr bool reference_is_exact = std::numeric_limits<wide>::digits >= std::numeric_limits<real>::digits + 10;

using hit_function = bool (*)(const rt::sphere&, const rt::ray&, real, real, rt::hit_record&);
struct method {
    const char* name;
    hit_function hit;
};
/// The textbook quadratic (Marschner, Shirley, Fundamentals of Computer
/// Graphics, 4th ed., sec. 4.4.1, eq. 4.6): the stage-03 exercise.
inline const method textbook{"textbook (stage 03's hit_sphere_textbook)", rt::hit_sphere_textbook};
inline const method stable{"stable", rt::hit_sphere};
inline const method both_methods[] = {textbook, stable};

/// "" when the stage-03 exercise runs, else its not-done message (a kit where
/// it is not written yet): the tables then leave the textbook's side out.
inline const std::string& textbook_not_done()
{
    static const std::string why = not_done_message([] {
        rt::sphere s;
        s.center = rt::vec3(0, 0, -5);
        rt::hit_record rec;
        rt::hit_sphere_textbook(s, rt::ray{rt::vec3(0), rt::vec3(0, 0, -1)}, 0, 1, rec);
    });
    return why;
}

/// For docs_figures: throws unless the tables' textbook side is the reference's
/// (require_reference_textbook): the figure is then skipped.
inline void require_textbook()
{
    require_reference_textbook(textbook_not_done(), "hit_sphere_textbook (stage 03)");
}

/// One unit in the last place of real at |x| (the gap to the next larger real).
inline wide ulp_at(wide x)
{
    const real magnitude = real(std::fabs(x));
    return wide(std::nextafter(magnitude, infinity)) - wide(magnitude);
}

/// |got - exact| in ulps of real at the exact value.
inline double error_ulps(real got, wide exact)
{
    return double(std::fabs(wide(got) - exact) / ulp_at(exact));
}

/// The stable method as the chapter gives it, with c = f.f - R^2 in real: the
/// library forms c in a wider type instead (include/rt/intersection/sphere.hpp), and the
/// ground table shows why. Only t is needed here.
inline bool hit_sphere_chapter_c_in_real(const rt::sphere& s, const rt::ray& r, real tmin, real tmax, rt::hit_record& rec)
{
    const rt::vec3 f = r.origin - s.center;
    const rt::vec3& d = r.direction;
    const real R = s.radius;
    const real a = glm::dot(d, d);
    const real b = glm::dot(f, d);
    const real c = glm::dot(f, f) - R * R;
    const rt::vec3 d_unit = d / std::sqrt(a);
    const rt::vec3 perpendicular = f - glm::dot(f, d_unit) * d_unit;
    const real discriminant = a * (R * R - glm::dot(perpendicular, perpendicular));
    if (!(discriminant >= 0))
        return false;
    const real q = -(b + std::copysign(std::sqrt(discriminant), b));
    const real t0 = std::min(c / q, q / a), t1 = std::max(c / q, q / a);
    const real t = tmin <= t0 ? t0 : t1;
    if (!(tmin <= t && t <= tmax))
        return false;
    rec.t = t;
    return true;
}
inline const method chapter_c_in_real{"chapter, c in real", hit_sphere_chapter_c_in_real};

/// The nearest root t >= 0 of |p + t d - c| = R, in long double, from the
/// ray's and the sphere's own reals. Products of two reals are exact in long
/// double (float) or nearly so (double, on x87), and the discriminant is
/// a (R^2 - |f x d|^2 / a) by Lagrange's identity, so nothing large cancels:
/// for the rays used here its error is orders of magnitude below one ulp of
/// real whenever reference_is_exact.
inline bool reference_root(const rt::sphere& s, const rt::ray& r, wide& t)
{
    const wide f[3] = {wide(r.origin.x) - s.center.x, wide(r.origin.y) - s.center.y, wide(r.origin.z) - s.center.z};
    const wide d[3] = {r.direction.x, r.direction.y, r.direction.z};
    const wide R = s.radius;
    const wide a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const wide b = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    const wide cross[3] = {f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2], f[0] * d[1] - f[1] * d[0]};
    const wide l2 = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) / a;
    const wide discriminant = a * (R * R - l2);
    if (discriminant < 0)
        return false;
    const wide c = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - R * R;
    const wide q = -(b + std::copysign(std::sqrt(discriminant), b));
    const wide t0 = std::min(c / q, q / a), t1 = std::max(c / q, q / a);
    t = t0 >= 0 ? t0 : t1;
    return t >= 0;
}

/// A unit sphere at distance D down the -z axis, and a ray along -z from
/// (h, 0, 0): it passes at distance h from the centre, so (FCG sec. 4.4.1 with
/// |d| = 1) its nearest root is exactly t = D - sqrt(1 - h^2).
struct axis_case {
    rt::sphere s;
    rt::ray r;
    wide exact;
};

inline axis_case axis_ray(real D, real h)
{
    axis_case k;
    k.s.center = rt::vec3(0, 0, -D);
    k.s.radius = 1;
    k.r.origin = rt::vec3(h, 0, 0);
    k.r.direction = rt::vec3(0, 0, -1);
    k.exact = wide(D) - std::sqrt(1 - wide(h) * wide(h)); // h has few bits: h^2 is exact
    return k;
}

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
inline void perpendiculars(const rt::vec3& u, rt::vec3& w, rt::vec3& v)
{
    const rt::vec3 axis = std::fabs(u.x) < real(0.5) ? rt::vec3(1, 0, 0) : rt::vec3(0, 1, 0);
    w = glm::normalize(glm::cross(u, axis));
    v = glm::cross(u, w);
}

/// `count` unit-direction rays in random oblique directions, each starting at
/// distance D from the centre of `s` and aimed at a random point (uniform in
/// area) of the ring between `reach_min` R and `reach_max` R around the centre,
/// in the plane through the centre perpendicular to the ray.
inline std::vector<rt::ray> oblique_fan(const rt::sphere& s, real D, real reach_min, real reach_max, int count,
                                 std::uint32_t seed)
{
    portable_random random(seed);
    std::vector<rt::ray> rays;
    for (int k = 0; k < count; ++k) {
        const rt::vec3 u = random.unit_vector();
        rt::vec3 w, v;
        perpendiculars(u, w, v);
        const real rho =
            s.radius * std::sqrt(reach_min * reach_min + (reach_max * reach_max - reach_min * reach_min) * random.uniform());
        const real phi = real(6.283185307179586) * random.uniform();
        const rt::vec3 offset = rho * (std::cos(phi) * w + std::sin(phi) * v);
        rays.push_back(rt::ray{s.center - D * u + offset, u});
    }
    return rays;
}

/// What one method did with one ray.
struct outcome {
    bool hit = false;
    double ulps = 0; ///< error of t in ulps at the exact root (when hit)
    wide depth_error = 0; ///< |t - exact| |d| / R (when hit)
};

inline outcome run(const method& m, const rt::sphere& s, const rt::ray& r, wide exact)
{
    outcome o;
    rt::hit_record rec;
    o.hit = m.hit(s, r, 0, infinity, rec);
    if (o.hit) {
        o.ulps = error_ulps(rec.t, exact);
        o.depth_error = std::fabs(wide(rec.t) - exact) * std::sqrt(wide(glm::dot(r.direction, r.direction))) / s.radius;
    }
    return o;
}

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

inline constexpr int fan_size = 256;
inline constexpr real fan_reach = real(0.9); // grazing oblique rays are ill-conditioned: see the doc
inline constexpr real miss_reach_min = real(1.1), miss_reach_max = real(2); // rays that pass the sphere
inline const real grazing_h = real(1) - real(1) / real(1024); // 1 - 2^-10: passes 0.001 R inside the silhouette

/// One row of the distance table.
struct distance_row {
    real D = 0;
    outcome centred[2], off_centre[2], grazing[2]; // [textbook, stable]; [0] empty while textbook_not_done()
    summary fan[2];      // rays that hit
    summary miss_fan[2]; // rays that pass at 1.1 R to 2 R from the centre
};

inline std::vector<distance_row> distance_table()
{
    std::vector<distance_row> rows;
    for (real D : {real(1e1), real(1e2), real(1e3), real(1e4), real(1e5), real(1e6)}) {
        distance_row row;
        row.D = D;
        const axis_case centred = axis_ray(D, 0), off = axis_ray(D, real(0.5)), grazing = axis_ray(D, grazing_h);
        rt::sphere fan_sphere;
        fan_sphere.center = rt::vec3(real(0.25), real(-0.5), real(0.75));
        const std::vector<rt::ray> fan = oblique_fan(fan_sphere, D, 0, fan_reach, fan_size, 2019);
        const std::vector<rt::ray> miss_fan =
            oblique_fan(fan_sphere, D, miss_reach_min, miss_reach_max, fan_size, 1999);
        for (int m = textbook_not_done().empty() ? 0 : 1; m < 2; ++m) {
            row.centred[m] = run(both_methods[m], centred.s, centred.r, centred.exact);
            row.off_centre[m] = run(both_methods[m], off.s, off.r, off.exact);
            row.grazing[m] = run(both_methods[m], grazing.s, grazing.r, grazing.exact);
            for (const rt::ray& r : fan) {
                wide exact = 0;
                if (reference_root(fan_sphere, r, exact)) // every fan ray hits: checked below
                    row.fan[m].add(run(both_methods[m], fan_sphere, r, exact));
            }
            for (const rt::ray& r : miss_fan) {
                wide exact = 0;
                if (!reference_root(fan_sphere, r, exact)) { // every one misses: checked below
                    ++row.miss_fan[m].rays;
                    rt::hit_record rec;
                    if (both_methods[m].hit(fan_sphere, r, 0, infinity, rec))
                        ++row.miss_fan[m].false_hits;
                }
            }
        }
        rows.push_back(row);
    }
    return rows;
}

/// A sphere of radius R centred at (0, -R, 0), its top at the origin, and a
/// ray from height h above the top, going down and sideways: d = (0.75, -1, 0).
/// All inputs have few bits, so the long-double quadratic is exact to its last
/// rounding (f = (0, R + h, 0), c = h (2R + h)).
struct ground_row {
    real R = 0, h = 0;
    wide exact = 0;
    outcome result[2]; // [textbook, stable]; [0] empty while textbook_not_done()
    outcome chapter; // the chapter's method with c in real
};

inline std::vector<ground_row> ground_table()
{
    std::vector<ground_row> rows;
    for (real R : {real(1e2), real(1e3), real(1e4), real(1e5)})
        for (real h : {real(1), real(0.25)}) {
            ground_row row;
            row.R = R;
            row.h = h;
            rt::sphere s;
            s.center = rt::vec3(0, -R, 0);
            s.radius = R;
            const rt::ray r{rt::vec3(0, h, 0), rt::vec3(real(0.75), -1, 0)};
            if (!reference_root(s, r, row.exact)) // cannot happen: the ray starts above the top, going down
                throw std::logic_error("the ground ray must hit: R = " + std::to_string(R) + ", h = " + std::to_string(h));
            for (int m = textbook_not_done().empty() ? 0 : 1; m < 2; ++m)
                row.result[m] = run(both_methods[m], s, r, row.exact);
            row.chapter = run(chapter_c_in_real, s, r, row.exact);
            rows.push_back(row);
        }
    return rows;
}

inline std::string cell(const outcome& o)
{
    std::ostringstream text;
    if (!o.hit)
        text << "miss";
    else
        text << std::fixed << std::setprecision(o.ulps < 100 ? 1 : 0) << o.ulps;
    return text.str();
}

inline std::string fan_cell(const summary& hits, const summary& misses)
{
    std::ostringstream text;
    text << std::fixed << std::setprecision(hits.worst_ulps < 100 ? 1 : 0) << hits.worst_ulps;
    if (hits.misses > 0)
        text << ", " << hits.misses << " missed";
    if (misses.false_hits > 0)
        text << ", " << misses.false_hits << " false hits";
    return text.str();
}

inline std::string depth_cell(wide depth_error)
{
    std::ostringstream text;
    text << std::setprecision(2) << double(depth_error);
    return text.str();
}

/// The exact root as the ground table prints it (9 significant digits).
inline std::string exact_text(wide exact)
{
    std::ostringstream text;
    text << std::setprecision(9) << double(exact);
    return text.str();
}

/// The two tables as Markdown, as the library suite prints them
/// (docs/stages/03-going-further.md quotes them cell by cell, through docs_figures).
inline std::string accuracy_tables()
{
    std::ostringstream table;
    const bool measured = textbook_not_done().empty();
    // the textbook's cell, or "-" where the stage-03 exercise is not written yet
    auto textbook_cell = [measured](const std::string& text) { return measured ? text : std::string("-"); };
    table << "\nrt::real = " << (real_is_float ? "float" : "double")
          << "; errors of t in ulps (textbook / stable); oblique fan: the worst of " << fan_size
          << " rays that hit, the misses among them, and the hits among " << fan_size << " rays that pass the sphere\n";
    if (!measured)
        table << "the textbook's cells are '-': " << textbook_not_done() << "\n";
    table << "| distance | centred | off-centre h = 0.5 | grazing h = 1 - 2^-10 | oblique fan, textbook | oblique fan, stable "
             "| oblique fan, textbook's worst depth error / R |\n"
          << "|---|---|---|---|---|---|---|\n";
    for (const distance_row& row : distance_table())
        table << "| " << std::setprecision(1) << std::scientific << double(row.D) << std::defaultfloat << " | "
              << textbook_cell(cell(row.centred[0])) << " / " << cell(row.centred[1]) << " | "
              << textbook_cell(cell(row.off_centre[0])) << " / " << cell(row.off_centre[1]) << " | "
              << textbook_cell(cell(row.grazing[0])) << " / " << cell(row.grazing[1]) << " | "
              << textbook_cell(fan_cell(row.fan[0], row.miss_fan[0])) << " | " << fan_cell(row.fan[1], row.miss_fan[1])
              << " | " << textbook_cell(depth_cell(row.fan[0].worst_depth_error)) << " |\n";
    table << "\nground sphere of radius R, ray d = (0.75, -1, 0) from height h above its top; errors in ulps\n"
          << "| R | h | exact t | textbook | stable, c in real (the chapter) | stable, c wider (rt) |\n"
          << "|---|---|---|---|---|---|\n";
    for (const ground_row& row : ground_table())
        table << "| " << std::setprecision(1) << std::scientific << double(row.R) << std::defaultfloat << " | "
              << std::setprecision(6) << double(row.h) << " | " << exact_text(row.exact) << " | "
              << textbook_cell(cell(row.result[0])) << " | " << cell(row.chapter) << " | " << cell(row.result[1]) << " |\n";
    return table.str();
}

} // namespace rt_test
