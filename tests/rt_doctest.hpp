// rt_doctest.hpp - doctest, with rt's values printed as a student can read them.
//
// Every suite includes this header instead of <doctest/doctest.h>. Without it a
// failed CHECK on a vector, a ray, a hit record or a box prints `{?} == {?}`,
// and an enum prints nothing useful; with it a failure shows the values, e.g.
//     CHECK( (0.5, 0.5, 1) == (0.5, 0.5, 0) )
//     CHECK( rec == ... ) with rec = {t 4, point (0, 0, -4), normal (0, 0, 1), front face, ...}
// (vectors, rays, hit records, boxes and camera windows: rt::window).
// Numbers are printed with enough digits to tell two neighbouring floats apart
// (std::numeric_limits<T>::max_digits10), so a failure at the last bit shows.
#pragma once

#include <doctest/doctest.h>

#include "rt_skip.hpp" // RT_SKIP

#include <cstddef>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

#include <rt/core/aabb.hpp>
#include <rt/scene/camera_model.hpp>
#include <rt/core/hit_record.hpp>
#include <rt/core/ray.hpp>
#include <rt/core/vec.hpp>

namespace rt_doctest {

template <class T>
void put_number(std::ostream& out, T x)
{
    if constexpr (std::is_floating_point_v<T>)
        out << std::setprecision(std::numeric_limits<T>::max_digits10) << x;
    else
        out << +x; // a uint8_t is a number here, not a character
}

template <glm::length_t L, class T, glm::qualifier Q>
std::string text(const glm::vec<L, T, Q>& v)
{
    std::ostringstream out;
    out << '(';
    for (glm::length_t k = 0; k < L; ++k) {
        if (k > 0)
            out << ", ";
        put_number(out, v[k]);
    }
    out << ')';
    return out.str();
}

inline std::string text(const rt::ray& r)
{
    return "ray{origin " + text(r.origin) + ", direction " + text(r.direction) + "}";
}

inline std::string text(const rt::hit_record& h)
{
    std::ostringstream out;
    out << "hit{t ";
    put_number(out, h.t);
    out << ", point " << text(h.point) << ", normal " << text(h.normal) << ", geometric normal "
        << text(h.geometric_normal) << ", " << (h.front_face ? "front face" : "back face") << ", material "
        << h.material << ", shape " << h.shape << ", primitive " << h.primitive << ", b1 ";
    put_number(out, h.b1);
    out << ", b2 ";
    put_number(out, h.b2);
    out << '}';
    return out.str();
}

inline std::string text(const rt::aabb& box)
{
    return "box{lo " + text(box.lo) + ", hi " + text(box.hi) + "}";
}

inline std::string text(const rt::window& w)
{
    std::ostringstream out;
    out << "window{l ";
    put_number(out, w.l);
    out << ", r ";
    put_number(out, w.r);
    out << ", b ";
    put_number(out, w.b);
    out << ", t ";
    put_number(out, w.t);
    out << '}';
    return out.str();
}

/// Whether rt has a name_of(E) for this enum (found by argument-dependent lookup).
template <class E, class = void>
struct has_name_of : std::false_type {};
template <class E>
struct has_name_of<E, std::void_t<decltype(name_of(std::declval<E>()))>> : std::true_type {};

/// The failures of one kind in a loop: how many, and the first in words, so a
/// check after the loop prints one message instead of one per failure:
///     problems bad;
///     for (...) if (!ok) bad.add([&](std::ostream& o) { o << "item " << k << " is ..."; });
///     CHECK_MESSAGE(bad.count == 0, bad.count << " items ...; the first: " << bad.first);
struct problems {
    std::size_t count = 0;
    std::string first;
    template <class Describe>
    void add(Describe&& describe)
    {
        if (count++ == 0) {
            std::ostringstream out;
            describe(out);
            first = out.str();
        }
    }
};

} // namespace rt_doctest

namespace doctest {

template <glm::length_t L, class T, glm::qualifier Q>
struct StringMaker<glm::vec<L, T, Q>> {
    static String convert(const glm::vec<L, T, Q>& v) { return rt_doctest::text(v).c_str(); }
};

template <>
struct StringMaker<rt::ray> {
    static String convert(const rt::ray& r) { return rt_doctest::text(r).c_str(); }
};

template <>
struct StringMaker<rt::hit_record> {
    static String convert(const rt::hit_record& h) { return rt_doctest::text(h).c_str(); }
};

template <>
struct StringMaker<rt::aabb> {
    static String convert(const rt::aabb& box) { return rt_doctest::text(box).c_str(); }
};

template <>
struct StringMaker<rt::window> {
    static String convert(const rt::window& w) { return rt_doctest::text(w).c_str(); }
};

} // namespace doctest

namespace rt {

/// An rt enum in a doctest message: its name where rt gives one (name_of), else
/// its enumerator's number. Found by argument-dependent lookup, in tests only.
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
std::ostream& operator<<(std::ostream& out, E value)
{
    if constexpr (rt_doctest::has_name_of<E>::value)
        return out << name_of(value);
    else
        return out << "enumerator #" << static_cast<long long>(static_cast<std::underlying_type_t<E>>(value));
}

} // namespace rt
