// accelerator.hpp - the library's nearest hit of a ray in a whole scene: what
// every stage program from 05 on traces with, and what stage 04's program
// compares the student's list and groups with (not an exercise). A header that
// only names rt::accelerator includes accelerator_fwd.hpp instead.
//
// rt::accelerator is built once from a scene, as a flat list of packed
// primitives or as a BVH (bvh.hpp), and returns exactly the same hits as the
// course's loop over the shapes (closest_hit_list, the stage-04 exercise in
// hit_list.hpp), faster:
//
//     rt::accelerator world(scene);                   // auto: BVH unless the scene is tiny
//     rt::hit_record rec;
//     if (world.closest_hit(r, 0, rt::infinity, rec)) ...  // rec.shape, rec.primitive, rec.material
//     if (world.any_hit(shadow_ray, 0, distance)) ...     // something blocks the light
//
// Closest means: the smallest t in [tmin, tmax]; at an equal t, the later
// primitive in scene order (shapes in file order, a mesh's triangles in its
// order), which is what the list loop does when it passes the closest t so far
// as tmax. The list, the flat accelerator and the BVH all follow this rule and
// all use the robust methods (rt::hit_sphere, the watertight triangle test), so
// they agree hit for hit.
//
// Every hit record is complete: t, point and its rounding error (for
// spawn_ray), geometric and shading normals facing the ray, front_face,
// material, shape, primitive, barycentrics. A sphere's hit point and normal
// are computed again from the ray relative to the centre, in a wider type
// (refine_sphere_hit), so the normal's direction does not depend on how far
// the ray came from.
//
// The BVH is walked by one of the fast paths (bvh_path): 8-wide nodes in AVX2
// where the CPU has it, else 4-wide nodes in SSE (x86-64), else 4-wide nodes
// one value at a time (arm64, rt::real = double). A program compiled without
// AVX2 in its target (-O2 alone) holds both x86-64 paths, with g++ and
// clang++ the 8-wide one also compiled for AVX-512 (avx512), and picks the
// widest the CPU runs when the accelerator is built (bvh/dispatch.hpp);
// simd_path() says which. All of them return the same hits, bit for bit
// (tests/library_dispatch.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "bvh.hpp"
#include "builtins.hpp"
#include "dispatch.hpp"
#include "hit_fill.hpp"
#include "../core/enum_names.hpp"
#include "../core/error.hpp"
#include "../core/hit_record.hpp"
#include "../scene/mesh.hpp"
#include "../core/ray.hpp"
#include "../scene/scene.hpp"
#include "../intersection/shape_hit.hpp"
#include "../intersection/sphere_stable.hpp"
#include "../scene/triangle_shape.hpp"
#include "../core/vec.hpp"

#include "simd_begin.hpp" // RT_BVH_INLINE, RT_BVH_DISPATCH, until bvh/simd_end.hpp

namespace rt {

/// How an accelerator searches the scene.
enum class accelerator_kind {
    flat,      ///< every primitive, in order (packed for speed)
    bvh,       ///< the bounding volume hierarchy of bvh.hpp
    automatic  ///< "auto": flat below flat_list_crossover primitives, else bvh
};

/// Below this many primitives the flat list is faster than the BVH: the
/// crossover that bench/groups.cpp measures (docs/performance.md, experiment 4).
constexpr std::size_t flat_list_crossover = 4;

/// The names of the accelerator kinds; the first is the default.
inline constexpr detail::enum_name<accelerator_kind> accelerator_names[] = {
    {accelerator_kind::automatic, "auto"}, {accelerator_kind::flat, "flat"}, {accelerator_kind::bvh, "bvh"}};

inline const char* name_of(accelerator_kind kind) { return detail::name_in(accelerator_names, kind); }

/// "flat", "bvh" or "auto"; anything else is an rt::error.
inline accelerator_kind parse_accelerator_kind(const std::string& word)
{
    if (const std::optional<accelerator_kind> kind = detail::value_named(accelerator_names, word))
        return *kind;
    throw error("expected an accelerator (flat, bvh or auto), found '" + word + "'");
}

/// The fast path an accelerator walks its BVH with (see the top of this file).
enum class bvh_path {
    automatic, ///< the fastest this program runs on this CPU (accelerator::automatic_path)
    scalar,    ///< 4-wide nodes, one value at a time: no SSE (arm64, rt::real = double)
    sse,       ///< 4-wide nodes in SSE (x86-64)
    avx2,      ///< 8-wide nodes in AVX2, where the CPU has it
    avx512     ///< the same, compiled for AVX-512 too (bvh/dispatch.hpp), where the CPU has it
};

/// The names of the BVH paths; the first is the default.
inline constexpr detail::enum_name<bvh_path> bvh_path_names[] = {
    {bvh_path::automatic, "auto"}, {bvh_path::scalar, "scalar"}, {bvh_path::sse, "sse"},
    {bvh_path::avx2, "avx2"},      {bvh_path::avx512, "avx512"}};

inline const char* name_of(bvh_path path) { return detail::name_in(bvh_path_names, path); }

/// "avx512 (8-wide)", "avx2 (8-wide)", "sse (4-wide)" or "scalar (4-wide)": a
/// path and its node width, for reports.
inline const char* describe(bvh_path path)
{
    switch (path) {
    case bvh_path::avx512: return "avx512 (8-wide)";
    case bvh_path::avx2: return "avx2 (8-wide)";
    case bvh_path::sse: return "sse (4-wide)";
    case bvh_path::scalar: return "scalar (4-wide)";
    case bvh_path::automatic: break;
    }
    return "auto";
}

/// Which shape, and which triangle inside a mesh, a packed primitive came from.
struct primitive_ref {
    std::uint32_t shape = 0;
    std::uint32_t primitive = 0;
};

inline namespace RT_BVH_ACCELERATOR_ABI { // this unit's paths (bvh/abi_begin.hpp)

/// The scene-level intersection: built once from a scene, then queried by
/// every ray. The scene must outlive the accelerator and must not change while
/// it is used. The queries are const and safe to call from many threads.
class accelerator {
public:
    accelerator() = default;

    /// `path`: the BVH's fast path (bvh_path::automatic: the fastest this
    /// program runs on this CPU); a path it does not run is an rt::error.
    explicit accelerator(const scene& s, accelerator_kind kind = accelerator_kind::automatic,
                         const bvh_options& options = {}, bvh_path path = bvh_path::automatic)
        : scene_(&s), path_(checked_path(path))
    {
        std::size_t count = 0;
        for (const shape& item : s.shapes)
            count += std::holds_alternative<mesh>(item) ? std::get<mesh>(item).triangles.size() : 1;
        if (count > std::size_t(sphere_flag - 1))
            throw error("expected at most 2^31 - 1 primitives in a scene, found " + std::to_string(count) +
                        "; split the scene");
        if (kind == accelerator_kind::automatic)
            kind = count < flat_list_crossover ? accelerator_kind::flat : accelerator_kind::bvh;
        kind_ = kind;
        // the packed primitives, in scene order (a shape's ids follow the
        // last shape's): the flat list keeps them; the BVH copies them into
        // its leaf blocks, so they are packed on the build's threads into an
        // array that is not first cleared (bvh/parallel_fill.hpp)
        first_id_.reserve(s.shapes.size() + 1);
        std::vector<packed_primitive, detail::default_init_allocator<packed_primitive>> prims(count);
        const int threads = detail::binary_builder::threads_for(count, options.threads);
        std::size_t id = 0;
        for (const shape& item : s.shapes) {
            first_id_.push_back(std::uint32_t(id));
            if (const sphere* ball = std::get_if<sphere>(&item)) {
                prims[id] = pack_sphere(*ball, std::uint32_t(id));
                ++id;
            } else if (const triangle* tri = std::get_if<triangle>(&item)) {
                prims[id] = pack_triangle(tri->a, tri->b, tri->c, std::uint32_t(id));
                ++id;
            } else {
                const mesh& m = std::get<mesh>(item);
                packed_primitive* out = prims.data() + id;
                const std::uint32_t first = std::uint32_t(id);
                detail::fill_in_parallel(m.triangles.size(), threads, [&](std::size_t begin, std::size_t end) {
                    for (std::size_t k = begin; k < end; ++k) {
                        const index3& face = m.triangles[k];
                        out[k] = pack_triangle(m.positions[face[0]], m.positions[face[1]], m.positions[face[2]],
                                               std::uint32_t(first + k));
                    }
                });
                id += m.triangles.size();
            }
        }
        first_id_.push_back(std::uint32_t(count));
        if (kind_ == accelerator_kind::flat)
            flat_.assign(prims.begin(), prims.end());
#if RT_BVH_DISPATCH
        else if (path_ == bvh_path::avx2)
            wide_.emplace(prims.data(), prims.size(), options); // bvh/dispatch.hpp
#endif
#if RT_BVH_DISPATCH_AVX512
        else if (path_ == bvh_path::avx512)
            wide512_.emplace(prims.data(), prims.size(), options);
#endif
        else
            tree_ = bvh(prims.data(), prims.size(), options);
    }

    /// Calls f(tree) with the BVH it walks (empty for a flat accelerator) and
    /// returns what f returns, the same type for every path: an rt::bvh, or
    /// where the program dispatches (bvh/dispatch.hpp) an rt::bvh_w8::bvh on
    /// the avx2 path and an rt::bvh_w8_avx512::bvh on the avx512 one.
    /// closest_hit, any_hit and stats go through it; the tests use it to look
    /// at the tree itself.
    template <class F>
    RT_BVH_INLINE decltype(auto) with_tree(F&& f) const
    {
#if RT_BVH_DISPATCH
        if (wide_)
            return f(*wide_);
#endif
#if RT_BVH_DISPATCH_AVX512
        if (wide512_)
            return f(*wide512_);
#endif
        return f(tree_);
    }

    /// The closest hit in [tmin, tmax] (see the top of this file), with every
    /// field of `rec` filled. Precondition: r.direction is not zero.
    RT_BVH_INLINE bool closest_hit(const ray& r, real tmin, real tmax, hit_record& rec) const
    {
        primitive_hit h;
        bool found = false;
        if (kind_ == accelerator_kind::flat)
            found = closest_hit_flat(flat_, r, tmin, tmax, h);
        else // a dispatched 8-wide walk is a call, never inlined here
            found = with_tree([&](const auto& tree) { return tree.closest_hit(r, tmin, tmax, h); });
        if (!found)
            return false;
        complete(r, tmin, tmax, h, rec);
        return true;
    }

    /// Whether anything is hit in [tmin, tmax]; cheaper than closest_hit
    /// because it stops at the first hit (shadow rays).
    bool any_hit(const ray& r, real tmin, real tmax) const
    {
        if (kind_ == accelerator_kind::flat)
            return any_hit_flat(flat_, r, tmin, tmax);
        return with_tree([&](const auto& tree) { return tree.any_hit(r, tmin, tmax); });
    }

    /// flat or bvh (automatic is resolved when the accelerator is built).
    accelerator_kind kind() const { return kind_; }
    std::size_t primitive_count() const { return first_id_.empty() ? 0 : first_id_.back(); }
    /// The BVH's statistics (all zero for a flat accelerator).
    const bvh_stats& stats() const
    {
        return with_tree([](const auto& tree) -> const bvh_stats& { return tree.stats(); });
    }

    /// The fast path its BVH is walked with (never automatic; a flat
    /// accelerator has the path it would have had, and tests its list one
    /// primitive at a time).
    bvh_path path() const { return path_; }
    /// describe(path()): "avx512 (8-wide)", "avx2 (8-wide)", "sse (4-wide)" or "scalar (4-wide)".
    const char* simd_path() const { return describe(path_); }

    /// Whether this program holds several paths and picks one per CPU (x86-64
    /// compiled without AVX2: bvh/dispatch.hpp): sse, avx2 or avx512.
    static constexpr bool dispatches = RT_BVH_DISPATCH != 0;
    /// Whether it also holds the 8-wide path compiled for AVX-512 (g++ and
    /// clang++ dispatching programs), which it walks where the CPU has AVX-512.
    static constexpr bool dispatches_avx512 = RT_BVH_DISPATCH_AVX512 != 0;

    /// The path bvh_path::automatic takes in this program on this CPU: avx512,
    /// else avx2, where the program holds it and the CPU runs it, else sse on
    /// x86-64, else scalar.
    static bvh_path automatic_path()
    {
#if RT_BVH_DISPATCH
        if (RT_BVH_DISPATCH_AVX512 && detail::cpu_runs_avx512())
            return bvh_path::avx512;
        return detail::cpu_runs_avx2() ? bvh_path::avx2 : bvh_path::sse;
#elif RT_BVH_AVX2
        return bvh_path::avx2;
#elif RT_BVH_SSE
        return bvh_path::sse;
#else
        return bvh_path::scalar;
#endif
    }

    /// The shape and primitive of a packed primitive's id (id < primitive_count()).
    /// Ids are given in scene order, so shape s holds the ids from
    /// first_id_[s] up to first_id_[s + 1]: the shape is the last one whose
    /// first id is <= id, found by a binary search without branches over the
    /// shapes' first ids (a few cached lines), not by a table of one entry per
    /// primitive, whose random lookup missed the cache on nearly every hit
    /// (docs/performance.md, experiment 6).
    RT_BVH_INLINE primitive_ref reference(std::uint32_t id) const
    {
        const std::uint32_t* first = first_id_.data();
        for (std::size_t n = first_id_.size() - 1; n > 1;) { // first[0] = 0 <= id
            const std::size_t half = n / 2;
            first = first[half] <= id ? first + half : first;
            n -= half;
        }
        return primitive_ref{std::uint32_t(first - first_id_.data()), id - *first};
    }

private:
    /// `asked`, or automatic_path() for automatic; an rt::error for a path
    /// this program does not hold or this CPU does not run.
    static bvh_path checked_path(bvh_path asked)
    {
        const bvh_path best = automatic_path();
        if (asked == bvh_path::automatic || asked == best)
            return best;
#if RT_BVH_DISPATCH
        if (asked == bvh_path::sse) // the dispatching program's other paths: sse on any x86-64
            return asked;
        if (asked == bvh_path::avx2 && detail::cpu_runs_avx2()) // and avx2 where avx512 is automatic
            return asked;
        if (asked == bvh_path::avx512 && !RT_BVH_DISPATCH_AVX512)
            throw error("expected a BVH path this program holds (auto, sse or avx2: MSVC compiles no AVX-512 path), "
                        "found 'avx512'");
        throw error(std::string("expected a BVH path this CPU runs (auto, sse") +
                    (detail::cpu_runs_avx2() ? " or avx2: it has no AVX-512" : ": it has no AVX2") + "), found '" +
                    name_of(asked) + "'");
#else
        throw error(std::string("expected a BVH path this program holds (auto or ") + name_of(best) +
                    ": it was compiled " + (best == bvh_path::avx2 ? "for AVX2" : "without dispatch") +
                    "), found '" + name_of(asked) + "'");
#endif
    }

    // inlined with closest_hit: a call kept the record's inputs and outputs in
    // memory
    RT_BVH_INLINE void complete(const ray& r, real tmin, real tmax, const primitive_hit& h, hit_record& rec) const
    {
        const primitive_ref ref = reference(h.id);
        const shape& item = scene_->shapes[ref.shape];
        if (const sphere* ball = std::get_if<sphere>(&item)) {
            hit_sphere(*ball, r, tmin, tmax, rec); // the same call as in the search: the same root
            detail::refine_sphere_hit(*ball, r, rec);
        } else {
            // the corners as packed (the same numbers as in the shape)
            const real* v = h.corners;
            const int k = h.stride;
            const triangle_hit hit{h.t, h.b0, h.b1, h.b2};
            if (h.normal != nullptr) { // stored by the BVH: triangle_normal of the corners
                detail::fill_triangle_record_strided(v, k, *h.normal, r, hit, rec); // bvh/hit_fill.hpp
            } else {
                const vec3 a(v[0], v[k], v[2 * k]), b(v[3 * k], v[4 * k], v[5 * k]), c(v[6 * k], v[7 * k], v[8 * k]);
                fill_triangle_record(a, b, c, r, hit, rec);
            }
            if (const triangle* tri = std::get_if<triangle>(&item))
                rec.material = tri->material;
            else
                complete_mesh_hit(std::get<mesh>(item), ref.primitive, rec);
        }
        rec.shape = ref.shape;
        rec.primitive = ref.primitive;
    }

    const scene* scene_ = nullptr;
    accelerator_kind kind_ = accelerator_kind::flat;
    bvh_path path_ = automatic_path();
    std::vector<std::uint32_t> first_id_; ///< shape s's first id, then the number of ids (see reference())
    std::vector<packed_primitive> flat_;
    bvh tree_; ///< the BVH of this unit's width (empty on the dispatched avx2 path)
#if RT_BVH_DISPATCH
    /// The 8-wide BVH, compiled for AVX2 (bvh/dispatch.hpp): made, walked and
    /// destroyed only on the avx2 path, so never on a CPU without AVX2.
    std::optional<bvh_w8::bvh> wide_;
#endif
#if RT_BVH_DISPATCH_AVX512
    /// The same, compiled for AVX-512 too: only on the avx512 path.
    std::optional<bvh_w8_avx512::bvh> wide512_;
#endif
};

} // namespace RT_BVH_ACCELERATOR_ABI

} // namespace rt

#include "simd_end.hpp"
