// wire.hpp - rt's values as bytes, for the judge and the student's server
// (tools/grading/judge/README.md).
//
// The server runs the student's code; the judge holds the tests. A call into a
// student's function crosses between them as bytes: its arguments one way, its
// return value and out-parameters back. The judge trusts nothing it reads back:
// every read checks the bytes left, a count is bounded by them, a bool is 0 or
// 1, an enum one of its values, a variant's index one of its types. A value
// that does not decode fails the call (wire_error), never the judge.
//
//     rt::judge::writer w;  w.put(rec);            // any type with a wire<T>
//     rt::judge::reader r(bytes);  r.get(rec);      // throws wire_error when short or bad
//
// Structs are sent field by field (fields<T> below), never as raw bytes, so a
// padding byte or an invalid bool never crosses. A struct that gains a field
// must gain it here too: the static_asserts on sizeof catch most of them.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <rt/core/error.hpp>

// rt's own types, when the reference is rt (the grader's tests use a small
// reference of ints alone, which has none of these headers)
#if __has_include(<rt/scene/scene.hpp>)
#include <rt/path_tracing/adaptive.hpp>
#include <rt/camera/camera.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/intersection/groups.hpp>
#include <rt/core/image.hpp>
#include <rt/path_tracing/lambertian.hpp>
#include <rt/scene/light.hpp>
#include <rt/path_tracing/mis.hpp>
#include <rt/core/random.hpp>
#include <rt/scene/scene.hpp>
#include <rt/input/scene_statement.hpp>
#include <rt/shading/shading.hpp>
#endif

namespace rt {
namespace judge {

/// Bytes that do not decode as the value expected.
class wire_error : public std::runtime_error {
public:
    explicit wire_error(const std::string& what) : std::runtime_error(what) {}
};

template <class T, class Enable = void>
struct wire;   // put(writer&, const T&) and get(reader&, T&), below

/// Gives a struct's fields, in order, to f (the same list for writing and reading).
template <class T>
struct fields;

class writer {
public:
    void raw(const void* data, std::size_t size) { bytes_.append(static_cast<const char*>(data), size); }
    template <class T>
    void put(const T& value) { wire<T>::put(*this, value); }
    const std::string& bytes() const { return bytes_; }
    std::string take() { return std::move(bytes_); }

private:
    std::string bytes_;
};

class reader {
public:
    reader(const char* data, std::size_t size) : at_(data), end_(data + size) {}
    explicit reader(const std::string& bytes) : reader(bytes.data(), bytes.size()) {}
    explicit reader(std::string&&) = delete;   // it would read a string that is gone

    void raw(void* data, std::size_t size)
    {
        if (std::size_t(end_ - at_) < size)
            throw wire_error("the reply ended early");
        std::memcpy(data, at_, size);
        at_ += size;
    }
    template <class T>
    void get(T& value) { wire<T>::get(*this, value); }
    template <class T>
    T get() { T value{}; get(value); return value; }

    /// A count of items of at least `smallest` bytes each: never more than the bytes left hold.
    std::size_t count(std::size_t smallest)
    {
        std::uint64_t n = 0;
        raw(&n, sizeof n);
        if (smallest == 0)
            smallest = 1;
        if (n > std::uint64_t(end_ - at_) / smallest)
            throw wire_error("a count larger than the reply");
        return std::size_t(n);
    }
    bool done() const { return at_ == end_; }

private:
    const char* at_;
    const char* end_;
};

// --- numbers, bools, enums ------------------------------------------------

template <class T>
struct wire<T, std::enable_if_t<std::is_arithmetic<T>::value && !std::is_same<T, bool>::value>> {
    static void put(writer& w, const T& x) { w.raw(&x, sizeof x); }
    static void get(reader& r, T& x) { r.raw(&x, sizeof x); }
};

template <>
struct wire<bool> {
    static void put(writer& w, const bool& x) { const std::uint8_t b = x ? 1 : 0; w.raw(&b, 1); }
    static void get(reader& r, bool& x)
    {
        std::uint8_t b = 0;
        r.raw(&b, 1);
        if (b > 1)
            throw wire_error("a bool that is neither true nor false");
        x = b == 1;
    }
};

/// The number of values of each enum that crosses (they count from 0).
template <class E> struct enum_size;

template <class E>
struct wire<E, std::enable_if_t<std::is_enum<E>::value>> {
    static void put(writer& w, const E& x) { w.put(std::int32_t(x)); }
    static void get(reader& r, E& x)
    {
        const auto v = r.get<std::int32_t>();
        if (v < 0 || v >= enum_size<E>::value)
            throw wire_error("an enum value out of range");
        x = E(v);
    }
};

// --- glm vectors, strings, containers --------------------------------------

template <>
struct wire<std::string> {
    static void put(writer& w, const std::string& s) { w.put(std::uint64_t(s.size())); w.raw(s.data(), s.size()); }
    static void get(reader& r, std::string& s)
    {
        s.resize(r.count(1));
        if (!s.empty())
            r.raw(&s[0], s.size());
    }
};

template <>
struct wire<std::filesystem::path> {
    static void put(writer& w, const std::filesystem::path& p) { w.put(p.string()); }
    static void get(reader& r, std::filesystem::path& p) { p = r.get<std::string>(); }
};

template <class T, class A>
struct wire<std::vector<T, A>> {
    static void put(writer& w, const std::vector<T, A>& v)
    {
        w.put(std::uint64_t(v.size()));
        for (const T& x : v)
            w.put(x);
    }
    static void get(reader& r, std::vector<T, A>& v)
    {
        v.clear();
        v.resize(r.count(1));
        for (T& x : v)
            r.get(x);
    }
};

template <class T, std::size_t N>
struct wire<std::array<T, N>> {
    static void put(writer& w, const std::array<T, N>& a) { for (const T& x : a) w.put(x); }
    static void get(reader& r, std::array<T, N>& a) { for (T& x : a) r.get(x); }
};

template <class T>
struct wire<std::optional<T>> {
    static void put(writer& w, const std::optional<T>& o)
    {
        w.put(o.has_value());
        if (o)
            w.put(*o);
    }
    static void get(reader& r, std::optional<T>& o)
    {
        o.reset();
        if (r.get<bool>())
            r.get(o.emplace());
    }
};

template <class... T>
struct wire<std::variant<T...>> {
    static void put(writer& w, const std::variant<T...>& v)
    {
        w.put(std::uint32_t(v.index()));
        std::visit([&](const auto& x) { w.put(x); }, v);
    }
    static void get(reader& r, std::variant<T...>& v)
    {
        const auto index = r.get<std::uint32_t>();
        if (index >= sizeof...(T))
            throw wire_error("a variant index out of range");
        emplace(r, v, index, std::index_sequence_for<T...>{});
    }

private:
    template <std::size_t... I>
    static void emplace(reader& r, std::variant<T...>& v, std::size_t index, std::index_sequence<I...>)
    {
        ((index == I ? (void)r.get(v.template emplace<I>()) : void()), ...);
    }
};

// --- structs, field by field -----------------------------------------------

template <class F, class... M>
void each_field(F& f, M&... m)
{
    (f(m), ...);
}

template <class T>
struct wire<T, std::void_t<decltype(sizeof(fields<T>))>> {
    static void put(writer& w, const T& x)
    {
        fields<T>::each(x, [&](const auto& m) { w.put(m); });
    }
    static void get(reader& r, T& x)
    {
        fields<T>::each(x, [&](auto& m) { r.get(m); });
    }
};

#if __has_include(<rt/scene/scene.hpp>)
template <> struct enum_size<projection> { static constexpr int value = 2; };
template <> struct enum_size<light_kind> { static constexpr int value = 4; };
template <> struct enum_size<path_strategy> { static constexpr int value = 4; };

template <glm::length_t N, class T, glm::qualifier Q>
struct wire<glm::vec<N, T, Q>> {
    static void put(writer& w, const glm::vec<N, T, Q>& v) { for (glm::length_t i = 0; i < N; ++i) w.put(v[i]); }
    static void get(reader& r, glm::vec<N, T, Q>& v) { for (glm::length_t i = 0; i < N; ++i) r.get(v[i]); }
};

// The field lists. Each names every member of its struct, in order.
template <> struct fields<ray> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.origin, x.direction); } };
template <> struct fields<aabb> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.lo, x.hi); } };
template <> struct fields<hit_record> {
    template <class X, class F>
    static void each(X& x, F f)
    {
        each_field(f, x.t, x.point, x.point_error, x.geometric_normal, x.normal, x.front_face, x.material, x.shape,
                   x.primitive, x.b1, x.b2);
    }
};
template <> struct fields<window> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.l, x.r, x.b, x.t); } };
template <> struct fields<camera> {
    template <class X, class F>
    static void each(X& x, F f) { each_field(f, x.kind, x.eye, x.look_at, x.up, x.fov_degrees, x.plane, x.focal_distance); }
};
template <> struct fields<lens_model> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.aperture, x.focus); } };
template <> struct fields<material> {
    template <class X, class F>
    static void each(X& x, F f)
    {
        each_field(f, x.name, x.ka, x.kd, x.ks, x.p, x.km, x.ior, x.attenuation, x.glossy, x.emission);
    }
};
template <> struct fields<light> {
    template <class X, class F>
    static void each(X& x, F f) { each_field(f, x.kind, x.position, x.direction, x.edge1, x.edge2, x.radius, x.intensity); }
};
template <> struct fields<light_sample> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.l, x.distance, x.intensity); } };
template <> struct fields<sphere> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.center, x.radius, x.material); } };
template <> struct fields<triangle> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.a, x.b, x.c, x.material); } };
template <> struct fields<mesh> {
    template <class X, class F>
    static void each(X& x, F f)
    {
        each_field(f, x.source, x.read_from, x.positions, x.triangles, x.normals, x.normal_indices, x.texcoords,
                   x.texcoord_indices, x.face_materials, x.material, x.dropped_degenerate);
    }
};
template <> struct fields<scene> {
    template <class X, class F>
    static void each(X& x, F f)
    {
        each_field(f, x.width, x.height, x.cam, x.lens, x.materials, x.lights, x.shapes, x.ambient, x.background,
                   x.samples, x.max_depth, x.default_material);
    }
};
template <> struct fields<frame> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.u, x.v, x.w); } };
template <> struct fields<ray_generator> {
    template <class X, class F>
    static void each(X& x, F f) { each_field(f, x.kind, x.e, x.basis, x.plane, x.d, x.nx, x.ny); }
};
template <> struct fields<image> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.width, x.height, x.pixels); } };
template <> struct fields<group_item> {
    template <class X, class F>
    static void each(X& x, F f) { each_field(f, x.shape, x.primitive, x.box, x.centroid); }
};
template <> struct fields<group_node> {
    template <class X, class F>
    static void each(X& x, F f) { each_field(f, x.box, x.first, x.count, x.left, x.right); }
};
template <> struct fields<groups> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.items, x.order, x.nodes); } };
template <> struct fields<pixel_statistics> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.s1, x.s2, x.n); } };
template <> struct fields<bsdf_sample> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.direction, x.pdf, x.weight); } };
template <> struct fields<emitter_sample> {
    template <class X, class F>
    static void each(X& x, F f) { each_field(f, x.point, x.normal, x.emission, x.pdf_area); }
};
template <> struct fields<token> { template <class X, class F> static void each(X& x, F f) { each_field(f, x.text, x.column); } };

// Every struct above, field for field: a member added to one of them and not
// to its list changes its size and stops the build here.
static_assert(sizeof(ray) == 2 * sizeof(vec3), "rt::ray changed: update fields<ray>");
static_assert(sizeof(frame) == 3 * sizeof(vec3), "rt::frame changed: update fields<frame>");
static_assert(sizeof(window) == 4 * sizeof(real), "rt::window changed: update fields<window>");
static_assert(sizeof(pixel_statistics) == 3 * sizeof(double), "rt::pixel_statistics changed: update its fields");  // s1, s2, n and padding
static_assert(sizeof(shading_options) == 2 * sizeof(void*), "rt::shading_options changed: update wire<shading_options>");

// --- the two classes with private state -------------------------------------

/// pcg32 is two 64-bit words, every value of which is a generator state.
template <>
struct wire<pcg32> {
    static_assert(sizeof(pcg32) == 2 * sizeof(std::uint64_t) && std::is_trivially_copyable<pcg32>::value,
                  "rt::pcg32 changed: update wire<pcg32>");
    static void put(writer& w, const pcg32& g) { w.raw(&g, sizeof g); }
    static void get(reader& r, pcg32& g) { r.raw(&g, sizeof g); }
};

// statement keeps its tokens private. An explicit instantiation may name a
// private member ([temp.explicit]/14), which is how these pointers to them are
// taken without changing rt's class for the grader.
template <class Tag, typename Tag::type Member>
struct private_member {
    friend typename Tag::type member_of(Tag) { return Member; }
};
struct statement_file { using type = std::string statement::*; friend type member_of(statement_file); };
struct statement_line { using type = int statement::*; friend type member_of(statement_line); };
struct statement_tokens { using type = std::vector<token> statement::*; friend type member_of(statement_tokens); };
struct statement_end { using type = int statement::*; friend type member_of(statement_end); };
struct statement_next { using type = std::size_t statement::*; friend type member_of(statement_next); };
template struct private_member<statement_file, &statement::file_>;
template struct private_member<statement_line, &statement::line_>;
template struct private_member<statement_tokens, &statement::tokens_>;
template struct private_member<statement_end, &statement::end_column_>;
template struct private_member<statement_next, &statement::next_>;

template <>
struct wire<statement> {
    static void put(writer& w, const statement& s)
    {
        w.put(s.*member_of(statement_file{}));
        w.put(s.*member_of(statement_line{}));
        w.put(s.*member_of(statement_tokens{}));
        w.put(s.*member_of(statement_end{}));
        w.put(std::uint64_t(s.*member_of(statement_next{})));
    }
    static void get(reader& r, statement& s)
    {
        r.get(s.*member_of(statement_file{}));
        r.get(s.*member_of(statement_line{}));
        r.get(s.*member_of(statement_tokens{}));
        r.get(s.*member_of(statement_end{}));
        const auto next = r.get<std::uint64_t>();
        const auto& tokens = s.*member_of(statement_tokens{});
        if (tokens.empty() || next < 1 || next > tokens.size())
            throw wire_error("a statement whose position is outside its words");
        s.*member_of(statement_next{}) = std::size_t(next);
    }
};

// shading_options points at the sample's generator, which the callee draws
// from: it crosses as its state, and the state comes back after the call (on
// the server, `random` points at a copy the call owns: holder in remote.hpp).
template <>
struct wire<shading_options> {
    static void put(writer& w, const shading_options& o)
    {
        w.put(o.light_falloff);
        w.put(o.random != nullptr);
        if (o.random != nullptr)
            w.put(*o.random);
    }
    // get: remote.hpp's holder, which owns the generator `random` points at
};

/// A statement to read into (it has no default constructor).
inline statement blank_statement() { return statement("", 0, {token{}}, 0); }
#endif // rt's own types


} // namespace judge
} // namespace rt
