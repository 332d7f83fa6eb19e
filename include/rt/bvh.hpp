// bvh.hpp - the fast path: a bounding volume hierarchy over packed primitives (stage 04).
//
// The course's group is a list searched from start to end; with n shapes every
// ray pays n intersection tests. A bounding volume hierarchy (BVH) puts the
// shapes in nested axis-aligned boxes, so a ray that misses a box skips all of
// its shapes: about log n box tests instead of n shape tests. This file is the
// engine behind rt::accelerator (intersect.hpp); the readable list is
// rt::closest_hit_list there, and the two return the same hits.
//
// Build (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
// IEEE Symposium on Interactive Ray Tracing 2007, sec. 3): top down, a binary
// tree; each node's primitives are sorted into `bins` equal slices of their
// centroids' extent on each axis, and the node is split at the slice boundary
// of least surface area heuristic cost (MacDonald, Booth, "Heuristics for ray
// tracing using space subdivision", The Visual Computer 6(3), 1990):
//     C = C_trav + C_isect (A_L B(N_L) + A_R B(N_R)) / A,
// A the surface areas of the boxes, N the primitive counts and B(N) =
// ceil(N / 4) the leaf tests they cost (a leaf is tested four primitives at a
// time, see below; Embree's builders count their four-triangle blocks the
// same way); a node becomes a leaf when that is cheaper than any split
// (C_isect B(N) <= C) and holds at most max_leaf_size primitives, or when it
// reaches max_depth. The binary tree is then collapsed into 4-wide nodes (see
// wide_collapser).
//
// Spatial splits (Stich, Friedrich, Dietrich, "Spatial Splits in Bounding
// Volume Hierarchies", HPG 2009): a large slanted triangle (a floor, a wall, a
// column of an architectural model) has a box far larger than itself, which
// overlaps its neighbours' boxes, so no plane between centroids separates
// them, and every ray through the box pays for it. At the top of the tree
// (binary_builder::build_spatial), a node whose best split above leaves two
// children overlapping by more than bvh_options::spatial_overlap of the
// root's area also tries planes that cut primitives: a primitive straddling
// the plane goes to both children, each with the box of its part only
// (detail::clipped_box, rounded outwards so it never cuts the triangle). The
// split is taken when its SAH cost is lower, within a budget of extra
// references (bvh_options::spatial_budget). A piece is the same triangle, so a
// ray gets the same hit through either; a leaf keeps one piece of each.
// On Sponza's incoherent rays this made traversal about 1.5x faster
// (docs/performance.md, experiment 6); on meshes of small triangles nothing
// is cut and the build is as before.
//
// Layout, and why:
//  - A node holds the boxes of up to four children, not its own box (as the
//    4-wide BVHs cited at wide_collapser do; Aila and Laine, "Understanding the
//    Efficiency of Ray Traversal on GPUs", HPG 2009, store two): one visit tests four boxes, and
//    a ray visits about half as many nodes as in a binary tree. The boxes are
//    stored plane by plane, bounds[lo x / hi x / lo y / hi y / lo z / hi z][child],
//    so that one 4-wide SIMD instruction treats the same plane of all four
//    children: a visit is 6 loads, 6 subtractions, 6 multiplications and 6
//    min/max, for four boxes. With the references a node is 128 bytes in
//    float, two cache lines, aligned.
//  - A child is an inner node (`child` is its index) or a leaf (`child` is
//    leaf_flag | its first block, `count` its primitives). Leaves cost no
//    node of their own. Nodes are stored flat in one array, depth first.
//  - A leaf's primitives are stored as blocks of four (triangle_block, 160
//    bytes in float), one array of blocks in the order the nodes meet the
//    leaves: the corners of four triangles as a structure of arrays (one row
//    per coordinate, one column per triangle), so that one SIMD instruction
//    does the same step of the watertight test for four triangles at once
//    (detail::intersect_block). Each triangle carries its corners, not indices
//    into a vertex array: a block is read in one sweep of consecutive cache
//    lines. Before blocks, a leaf held 1.9 triangles on average (the SAH
//    counted each one) and each was an out-of-line scalar test; the SAH now
//    counts blocks, leaves hold about 5 triangles in 1.35 blocks, the tree has
//    a third of the nodes, and a ray visits fewer of them (docs/performance.md,
//    experiment 6). The test is decided lane by lane with the scalar test's
//    operations in the same order, so both give the same bits, and the
//    blocks need no mask: an unused lane holds NaN corners, whose t the range
//    test refuses.
//  - The packed primitives (packed_primitive, 40 bytes) are kept too, in leaf
//    order (bvh::primitives(), for the tests; a primitive cut by spatial
//    splits is there once per piece); traversal reads only the nodes and the
//    blocks, and a hit's corners are read from its block.
//  - Per ray, traversal precomputes the reciprocal direction and, per axis,
//    which plane row of a node is met first (the sign of the reciprocal), so a
//    box test is a subtraction and a multiplication per plane, no division and
//    no branch. The watertight test's axis permutation and shear are also
//    precomputed once per ray.
//  - Children are visited nearest first: the nearest child met is entered and
//    the others go on a fixed-size stack with their entry distances; an entry
//    whose distance is beyond the closest hit found meanwhile is skipped when
//    popped. The stack is a local array: no allocation per ray. any() returns
//    at the first hit (shadow rays), and pushes the children unsorted: their
//    order cannot change its answer.
//  - The order is found with one jump on the 4-bit mask of children met (a
//    switch over the 15 masks, each case a template that knows its children at
//    compile time: bvh::descend). On coherent rays the jump is predicted and
//    the processor loads the next node before the box test has finished; on
//    incoherent rays a visit costs at most one misprediction, where a loop
//    over the four bits and an insertion sort cost several (cachegrind: 29
//    branch misses per incoherent ray on the bunny). Two children are ordered
//    by a select, three or four by ranking their distances in SIMD
//    (detail::order_children), both without a branch. A version that ranked
//    every visit without any branch was 2x slower on coherent rays: the next
//    node's address then waits for the box test, which a predicted branch
//    does not.
//  - With SSE2 (every x86-64 compiler, no -march needed) the four boxes and
//    the four triangles of a block are tested in 4-wide registers (the edge
//    functions in double, two lanes per register, or four with AVX);
//    elsewhere, and for rt::real = double, the same arithmetic runs one value
//    at a time (intersect_children_scalar, intersect_block_scalar,
//    bvh::closest_scalar). Both give identical results.
//
// The slab test is robust (Williams, Barrus, Morley, Shirley, "An Efficient and
// Robust Ray-Box Intersection Algorithm", Journal of Graphics Tools 10(1),
// 2005; Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013):
//  - 1/d is computed as IEEE gives it: +-inf for a zero component, the sign
//    following the sign of zero (-0 gives -inf), so axis-parallel rays and -0
//    need no special case; the near plane of each axis is chosen by the sign
//    of 1/d.
//  - A ray lying in a slab plane gives (plane - o) * inf = 0 * inf = NaN. Each
//    comparison is written so that a NaN leaves the running interval as it was:
//    the ray counts as inside that slab (the box is closed), never as outside,
//    and no NaN reaches a result.
//  - Rounding can make the computed t_far smaller than the computed t_near
//    when the exact values are equal (a ray through a box edge or corner, and
//    a triangle's box is touched by the triangle at its corners). Ize shows the
//    computed values are within gamma_3 of the exact ones, so comparing
//    t_near <= t_far (1 + 2 gamma_3) never culls a box the ray truly meets.
//    The factor is applied to min(t_far, t_max), so a hit at exactly the
//    current closest t is not culled either.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

// RT_BVH_SSE: SSE2 is there (every x86-64 compiler) and rt::real is float.
// Defined here and undefined at the end of this file.
#if (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)) && \
    !(defined(RT_USE_DOUBLE) && RT_USE_DOUBLE)
#define RT_BVH_SSE 1
#else
#define RT_BVH_SSE 0
#endif

#if RT_BVH_SSE
#include <emmintrin.h>
#endif

// RT_BVH_AVX: AVX is there too (-mavx, -march=native on a recent x86-64): the
// leaf test then converts four lanes to double at once. Undefined at the end.
#if RT_BVH_SSE && defined(__AVX__)
#define RT_BVH_AVX 1
#include <immintrin.h>
#else
#define RT_BVH_AVX 0
#endif

#include "aabb.hpp"
#include "error.hpp"
#include "hit_record.hpp"
#include "ray.hpp"
#include "rounding.hpp"
#include "sphere_stable.hpp"
#include "vec.hpp"
#include "watertight.hpp"

namespace rt {

// --- primitives laid out for traversal ---------------------------------------

/// Set in packed_primitive::id for a sphere.
constexpr std::uint32_t sphere_flag = 0x80000000u;

/// One primitive as traversal reads it: a triangle's corners a, b, c (v[0..8])
/// or a sphere's centre (v[0..2]) and radius (v[3]); `id` is the primitive's
/// number in scene order, with sphere_flag set for spheres.
struct packed_primitive {
    real v[9];
    std::uint32_t id;
};

inline packed_primitive pack_triangle(const vec3& a, const vec3& b, const vec3& c, std::uint32_t id)
{
    return packed_primitive{{a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}, id};
}

inline packed_primitive pack_sphere(const sphere& s, std::uint32_t id)
{
    return packed_primitive{{s.center.x, s.center.y, s.center.z, s.radius, 0, 0, 0, 0, 0}, id | sphere_flag};
}

/// A box that contains the primitive. A triangle's box is exact (the min and
/// max of its corners); a sphere's is widened by a few ulps, because c +- R
/// is rounded and the box must not cut the sphere.
inline aabb packed_bounds(const packed_primitive& p)
{
    aabb box;
    if (p.id & sphere_flag) {
        const vec3 c(p.v[0], p.v[1], p.v[2]);
        const real r = p.v[3];
        const vec3 margin = gamma_n(4) * (glm::abs(c) + vec3(r));
        box.lo = c - vec3(r) - margin;
        box.hi = c + vec3(r) + margin;
    } else {
        for (int k = 0; k < 3; ++k)
            box.grow(vec3(p.v[3 * k], p.v[3 * k + 1], p.v[3 * k + 2]));
    }
    return box;
}

/// A hit on a packed primitive: t, the barycentrics (triangles only), the
/// primitive's number in scene order (without sphere_flag) and, for a
/// triangle, where its corners were read: coordinate j (a.x a.y a.z b.x ...)
/// at corners[j * stride] (a packed_primitive: stride 1; a lane of a
/// triangle_block: stride 4). They are in cache: completing the hit record
/// reads them there rather than through the mesh's index arrays.
struct primitive_hit {
    real t = 0;
    real b0 = 0, b1 = 0, b2 = 0;
    std::uint32_t id = 0;
    const real* corners = nullptr;
    int stride = 1;
};

/// The one rule for "closest": a smaller t wins; at an equal t the later
/// primitive in scene order wins, as in the course's list loop, which passes
/// the closest t so far as tmax and so accepts a later hit at the same t.
/// With it the flat list and the BVH return the same hit whatever the order
/// of their tests.
inline bool replaces(const primitive_hit& candidate, const primitive_hit& best)
{
    return candidate.t < best.t || (candidate.t == best.t && candidate.id > best.id);
}

/// Intersects one packed primitive with the library's default methods: the
/// watertight triangle test and rt::hit_sphere.
inline bool intersect_packed(const packed_primitive& p, const ray& r, const watertight_ray& w, real tmin, real tmax,
                             primitive_hit& hit)
{
    if (p.id & sphere_flag) {
        sphere s;
        s.center = vec3(p.v[0], p.v[1], p.v[2]);
        s.radius = p.v[3];
        hit_record rec;
        if (!hit_sphere(s, r, tmin, tmax, rec))
            return false;
        hit.t = rec.t;
        hit.b0 = hit.b1 = hit.b2 = 0;
        hit.id = p.id & ~sphere_flag;
        hit.corners = nullptr;
        return true;
    }
    triangle_hit h;
    if (!intersect_watertight(w, p.v, tmin, tmax, h))
        return false;
    hit.t = h.t;
    hit.b0 = h.b0;
    hit.b1 = h.b1;
    hit.b2 = h.b2;
    hit.id = p.id;
    hit.corners = p.v;
    hit.stride = 1;
    return true;
}

/// Up to four primitives of one leaf as the SIMD leaf test reads them (see the
/// top of this file): the triangles' corners as a structure of arrays,
/// v[3 corner + axis][lane] (row 0 is a.x of the four triangles, row 4 b.y),
/// so that one 4-wide load gives the same coordinate of four triangles, and
/// their ids (packed_primitive::id). A sphere's lane holds its centre and
/// radius in rows 0 to 3, NaN in the others, and sphere_flag in its id, the
/// sign bit of the lane (one movemask finds the spheres of a block). A lane
/// that a leaf does not fill is NaN with id 0. NaN corners give a NaN t, which
/// the range test refuses, so the triangle test needs no mask of its own.
/// 160 bytes in float, the size of four packed_primitive.
struct alignas(32) triangle_block {
    real v[9][4];
    std::uint32_t id[4];
};

/// The block of prims[first, first + n), n <= 4.
inline triangle_block pack_triangle_block(const packed_primitive* prims, std::size_t first, std::size_t n)
{
    triangle_block b;
    for (int j = 0; j < 9; ++j)
        for (int lane = 0; lane < 4; ++lane)
            b.v[j][lane] = std::numeric_limits<real>::quiet_NaN();
    for (std::size_t lane = 0; lane < 4; ++lane) {
        b.id[lane] = 0;
        if (lane >= n)
            continue;
        const packed_primitive& p = prims[first + lane];
        b.id[lane] = p.id;
        for (int j = 0; j < ((p.id & sphere_flag) ? 4 : 9); ++j)
            b.v[j][lane] = p.v[j];
    }
    return b;
}

/// The flat list over packed primitives: every primitive tested, the closest
/// kept by replaces(). For scenes too small to pay for a BVH.
inline bool closest_flat(const std::vector<packed_primitive>& prims, const ray& r, real tmin, real tmax,
                         primitive_hit& best)
{
    const watertight_ray w = make_watertight_ray(r);
    bool found = false;
    for (const packed_primitive& p : prims) {
        primitive_hit h;
        if (intersect_packed(p, r, w, tmin, found ? best.t : tmax, h) && (!found || replaces(h, best))) {
            best = h;
            found = true;
        }
    }
    return found;
}

/// Whether any packed primitive is hit in [tmin, tmax].
inline bool any_flat(const std::vector<packed_primitive>& prims, const ray& r, real tmin, real tmax)
{
    const watertight_ray w = make_watertight_ray(r);
    primitive_hit h;
    for (const packed_primitive& p : prims)
        if (intersect_packed(p, r, w, tmin, tmax, h))
            return true;
    return false;
}

// --- the robust slab test ----------------------------------------------------

/// Ize 2013: the computed t_far is scaled by 1 + 2 gamma_3 before it is
/// compared with t_near, so that rounding never culls a box the ray meets.
constexpr real slab_far_factor = 1 + 2 * gamma_n(3);

/// A ray prepared for box tests: its origin, 1/d (+-inf for a +-0
/// component) and, per axis, 1 when 1/d is negative (the near plane is hi).
struct box_ray {
    vec3 origin{0};
    vec3 inv_dir{0};
    int negative[3] = {0, 0, 0};
};

inline box_ray make_box_ray(const ray& r)
{
    box_ray b;
    b.origin = r.origin;
    for (int k = 0; k < 3; ++k) {
        b.inv_dir[k] = real(1) / r.direction[k]; // IEEE: 1/+0 = +inf, 1/-0 = -inf
        b.negative[k] = std::signbit(b.inv_dir[k]) ? 1 : 0;
    }
    return b;
}

/// The robust slab test (see the top of this file): true when the ray meets
/// `box` within [tmin, tmax]; `tnear` is then where it enters. `far_factor`
/// is Ize's 1 + 2 gamma_3; the tests pass 1 to show what goes wrong without it.
inline bool hit_box(const aabb& box, const box_ray& r, real tmin, real tmax, real& tnear,
                    real far_factor = slab_far_factor)
{
    real t0 = tmin, t1 = tmax;
    for (int k = 0; k < 3; ++k) {
        const real near_plane = r.negative[k] ? box.hi[k] : box.lo[k];
        const real far_plane = r.negative[k] ? box.lo[k] : box.hi[k];
        const real t_near = (near_plane - r.origin[k]) * r.inv_dir[k];
        const real t_far = (far_plane - r.origin[k]) * r.inv_dir[k];
        t0 = t_near > t0 ? t_near : t0; // a NaN (ray in this plane) keeps t0
        t1 = t_far < t1 ? t_far : t1;   // a NaN keeps t1
    }
    tnear = t0;
    return t0 <= t1 * far_factor;
}

// --- the hierarchy -----------------------------------------------------------

/// How a BVH is built (see the top of this file). The defaults were chosen by
/// measuring primary rays on the Stanford bunny (docs/stages/04-triangle.md).
struct bvh_options {
    int bins = 16;                    ///< SAH slices per axis and node
    std::size_t max_leaf_size = 8;    ///< a node with more primitives is always split
    real traversal_cost = 1;          ///< C_trav: one node visit
    real intersection_cost = 1;       ///< C_isect: one leaf test of up to primitives_per_test primitives
    std::size_t primitives_per_test = 4; ///< the SAH counts a leaf's primitives in blocks of this many
    int max_depth = 60;               ///< a node this deep in the binary tree becomes a leaf
    int threads = 0;                  ///< threads for the build; 0: one per core (the tree is the same)
    /// Spatial splits (see binary_builder::build_spatial): at most this many
    /// extra references, as a fraction of the primitives; 0 turns them off.
    real spatial_budget = real(0.3);
    /// A node tries spatial splits when its best object split's children
    /// overlap by more than this fraction of the root's surface area. Stich
    /// et al. use 1e-5; 3e-3 keeps Sponza's gain at about half the extra
    /// build time (docs/performance.md, experiment 6).
    real spatial_overlap = real(3e-3);
};

/// What a build produced.
struct bvh_stats {
    std::size_t primitives = 0;
    std::size_t references = 0;   ///< primitives plus the extra pieces made by spatial splits
    std::size_t spatial_splits = 0; ///< binary nodes split by a plane that cuts primitives
    std::size_t nodes = 0;        ///< 4-wide nodes
    std::size_t leaves = 0;
    std::size_t binary_nodes = 0; ///< inner nodes of the binary tree before collapsing
    int depth = 0;                ///< the deepest leaf: the root's children are at depth 1
    double sah_cost = 0;          ///< the binary tree's SAH cost, in units of one primitive test
};

/// One 4-wide node (see the top of this file): the boxes of up to four
/// children, plane by plane, and their references. 128 bytes in float.
struct alignas(64) bvh_node {
    /// bounds[2 k][c] = lo of child c on axis k, bounds[2 k + 1][c] = hi; an
    /// unused child has the empty box lo = +inf, hi = -inf, which no ray meets.
    real bounds[6][4];
    std::uint32_t child[4];  ///< an inner child's node index, or leaf_flag | its first primitive
    std::uint32_t count[4];  ///< a leaf's number of primitives (0 for inner children)
};

/// Set in bvh_node::child for a leaf.
constexpr std::uint32_t leaf_flag = 0x80000000u;

namespace detail {

/// A primitive during the build: its box, its centroid and where it came from.
struct build_item {
    aabb box;
    vec3 centroid{0};
    std::uint32_t index = 0;
};

inline real half_area(const aabb& box)
{
    if (box.empty())
        return 0;
    const vec3 e = box.extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
}


/// Rounds a double to the nearest real below it (down) or above it.
inline real round_outwards(double x, bool down)
{
    real r = real(x);
    if (down && double(r) > x)
        r = std::nextafter(r, -std::numeric_limits<real>::infinity());
    if (!down && double(r) < x)
        r = std::nextafter(r, std::numeric_limits<real>::infinity());
    return r;
}

/// The box of the part of primitive p inside `within` and on one side of the
/// plane x[axis] = s (below: x[axis] <= s, else x[axis] >= s); empty when
/// there is no such part. It never cuts the primitive: a triangle's corners
/// on that side and the points where its edges cross the plane (computed in
/// double, widened by more than their rounding error and rounded outwards),
/// then cut to `within`; a sphere's is `within` cut at the plane.
inline aabb clipped_box(const packed_primitive& p, int axis, real s, bool below, const aabb& within)
{
    aabb box;
    if (p.id & sphere_flag) {
        box = within;
    } else {
        for (int i = 0; i < 3; ++i) {
            const real* u = p.v + 3 * i;
            const real* v = p.v + 3 * ((i + 1) % 3);
            if (below ? u[axis] <= s : u[axis] >= s)
                box.grow(vec3(u[0], u[1], u[2]));
            if ((u[axis] < s && v[axis] > s) || (u[axis] > s && v[axis] < s)) {
                const double t = (double(s) - double(u[axis])) / (double(v[axis]) - double(u[axis]));
                vec3 lo, hi;
                for (int k = 0; k < 3; ++k) {
                    if (k == axis) {
                        lo[k] = hi[k] = s;
                        continue;
                    }
                    const double x = double(u[k]) + t * (double(v[k]) - double(u[k]));
                    const double margin = 16 * std::numeric_limits<double>::epsilon() *
                                          (std::abs(double(u[k])) + std::abs(double(v[k])));
                    lo[k] = round_outwards(x - margin, true);
                    hi[k] = round_outwards(x + margin, false);
                }
                box.grow(lo);
                box.grow(hi);
            }
        }
        box.lo = glm::max(box.lo, within.lo);
        box.hi = glm::min(box.hi, within.hi);
    }
    if (below)
        box.hi[axis] = std::min(box.hi[axis], s);
    else
        box.lo[axis] = std::max(box.lo[axis], s);
    return box;
}

/// A child of a binary node: inner (count 0, `index` a binary node) or a leaf
/// (`count` primitives from `index`).
struct binary_child {
    aabb box;
    std::uint32_t index = 0;
    std::uint32_t count = 0;
};

struct binary_node {
    binary_child side[2];
};

/// The binned SAH build of a binary tree (see the top of this file).
///
/// Speed: one pass over a node's primitives bins them on all three axes at
/// once; the two halves of the top of the tree are built on separate threads
/// (bvh_options::threads), each into its own node array, and the arrays are
/// joined in the order a single thread writes them, so the tree is the same
/// whatever the number of threads.
class binary_builder {
public:
    /// A split of a node by the SAH: the axis, where, its cost and the children's boxes.
    struct split {
        int axis = -1;
        std::size_t bin = 0;  ///< the first bin of the right side
        real cost = 0;        ///< A_L N_L + A_R N_R
        aabb left, right;
    };

    binary_builder(std::vector<build_item>& items, const bvh_options& options, int spare_threads,
                   const packed_primitive* prims = nullptr)
        : items_(items), options_(options), spare_threads_(spare_threads), prims_(prims),
          bin_count_(std::size_t(std::max(2, std::min(options.bins, 256))))
    {
        for (int axis = 0; axis < 3; ++axis)
            bins_[axis].resize(bin_count_);
        right_cost_.resize(bin_count_);
        right_box_.resize(bin_count_);
    }

    std::vector<binary_node> nodes;
    double sah_cost = 0; ///< the sum of C A over the subtree, before dividing by the root's area
    std::size_t spatial_splits = 0;

    /// The top of the tree with spatial splits (Stich, Friedrich, Dietrich,
    /// "Spatial Splits in Bounding Volume Hierarchies", HPG 2009). `refs` are
    /// this node's references (moved in, freed before the children are
    /// built). A node whose best object split leaves two children that
    /// overlap by more than spatial_overlap of the root's area also bins its
    /// references between planes that may cut them (find_spatial_split); if
    /// that costs less by the SAH, a reference that straddles the plane goes
    /// to both children, each with the box of its part (clipped_box). The
    /// pieces are references to the same primitive, so a ray gets the same
    /// hit whichever it meets. A node where the overlap is small, or whose
    /// subtree is small, is handed to build(), in place at the end of items_.
    binary_child build_spatial(std::vector<build_item> refs, const aabb& box, int depth, real root_area,
                               std::size_t& budget)
    {
        const std::size_t n = refs.size();
        const auto hand_over = [&](const split* known = nullptr, const aabb* centroids = nullptr) {
            const std::size_t begin = items_.size();
            items_.insert(items_.end(), refs.begin(), refs.end());
            std::vector<build_item>().swap(refs);
            return build(begin, items_.size(), box, depth, known, centroids);
        };
        if (n <= options_.max_leaf_size || depth + 1 >= options_.max_depth || budget == 0)
            return hand_over();
        // a node where every reference is narrower than a slice on every
        // axis gains nothing from cutting them (a fine mesh, or the lower
        // part of the tree): build() does it in place and on threads
        aabb centroids;
        bool wide[3] = {false, false, false};
        const vec3 slice_width = box.extent() / real(bin_count_);
        for (const build_item& r : refs) {
            centroids.grow(r.centroid);
            const vec3 e = r.box.extent();
            for (int axis = 0; axis < 3; ++axis)
                wide[axis] = wide[axis] || e[axis] > slice_width[axis];
        }
        if (!wide[0] && !wide[1] && !wide[2])
            return hand_over(nullptr, &centroids);
        const split object = find_split(refs.data(), n, centroids);
        if (object.axis < 0)
            return hand_over(&object, &centroids);
        aabb overlap;
        overlap.lo = glm::max(object.left.lo, object.right.lo);
        overlap.hi = glm::min(object.left.hi, object.right.hi);
        if (overlap.empty() || !(half_area(overlap) > options_.spatial_overlap * root_area))
            return hand_over(&object, &centroids);
        const spatial_split cut = find_spatial_split(refs, box, wide);

        std::vector<build_item> left, right;
        if (cut.axis >= 0 && cut.cost < object.cost && cut.extra <= budget) {
            for (const build_item& r : refs) {
                if (r.box.hi[cut.axis] <= cut.plane) {
                    left.push_back(r);
                } else if (r.box.lo[cut.axis] >= cut.plane) {
                    right.push_back(r);
                } else {
                    const aabb below = clipped_box(prims_[r.index], cut.axis, cut.plane, true, r.box);
                    const aabb above = clipped_box(prims_[r.index], cut.axis, cut.plane, false, r.box);
                    if (below.empty()) {
                        right.push_back(r);
                    } else if (above.empty()) {
                        left.push_back(r);
                    } else {
                        left.push_back(build_item{below, below.center(), r.index});
                        right.push_back(build_item{above, above.center(), r.index});
                    }
                }
            }
            if (left.empty() || right.empty()) {
                std::vector<build_item>().swap(left);
                std::vector<build_item>().swap(right);
            } else {
                budget -= std::min(budget, left.size() + right.size() - n);
                ++spatial_splits;
            }
        }
        if (left.empty() && right.empty()) { // the object split, as build() makes it
            const real low = centroids.lo[object.axis];
            const real scale = real(bin_count_) / (centroids.hi[object.axis] - low);
            for (const build_item& r : refs)
                (bin_of(r.centroid[object.axis], low, scale) < object.bin ? left : right).push_back(r);
        }
        std::vector<build_item>().swap(refs);
        aabb left_box, right_box;
        for (const build_item& r : left)
            left_box.grow(r.box);
        for (const build_item& r : right)
            right_box.grow(r.box);

        // the budget left is shared by the children in proportion to their
        // references, so the tree does not depend on which is built first
        std::size_t right_budget =
            std::size_t(double(budget) * double(right.size()) / double(left.size() + right.size()));
        std::size_t left_budget = budget - right_budget;
        budget = 0;
        const std::size_t index = nodes.size();
        nodes.emplace_back();
        sah_cost += double(options_.traversal_cost) * double(half_area(box));
        binary_child l, r;
        if (spare_threads_ > 0 && n >= parallel_threshold) {
            // the right child into an item array of its own: it appends to it
            std::vector<build_item> right_items;
            build_in_parallel(
                right_items, l, r,
                [&] { return build_spatial(std::move(left), left_box, depth + 1, root_area, left_budget); },
                [&](binary_builder& b) {
                    return b.build_spatial(std::move(right), right_box, depth + 1, root_area, right_budget);
                });
        } else {
            l = build_spatial(std::move(left), left_box, depth + 1, root_area, left_budget);
            r = build_spatial(std::move(right), right_box, depth + 1, root_area, right_budget);
        }
        nodes[index].side[0] = l;
        nodes[index].side[1] = r;
        binary_child inner;
        inner.box = box;
        inner.index = std::uint32_t(index);
        return inner;
    }

    /// Builds the subtree of items [begin, end) inside `box`; returns it as a
    /// child. `known` and `known_centroids`, when given, are this node's best
    /// split and centroid box, already found by build_spatial.
    binary_child build(std::size_t begin, std::size_t end, const aabb& box, int depth, const split* known = nullptr,
                       const aabb* known_centroids = nullptr)
    {
        const std::size_t n = end - begin;
        const real area = half_area(box);
        if (n <= 1 || depth >= options_.max_depth)
            return leaf(begin, n, box, area);

        aabb centroids;
        if (known_centroids != nullptr)
            centroids = *known_centroids;
        else
            for (std::size_t i = begin; i < end; ++i)
                centroids.grow(items_[i].centroid);

        aabb left_box, right_box;
        std::size_t middle = begin;
        const split best = known != nullptr ? *known : find_split(items_.data() + begin, n, centroids);
        if (best.axis < 0) {
            // every centroid is the same point: no plane separates them
            if (n <= options_.max_leaf_size)
                return leaf(begin, n, box, area);
            middle = begin + n / 2;
            for (std::size_t i = begin; i < middle; ++i)
                left_box.grow(items_[i].box);
            for (std::size_t i = middle; i < end; ++i)
                right_box.grow(items_[i].box);
        } else {
            const real split_cost =
                area > 0 ? options_.traversal_cost + options_.intersection_cost * best.cost / area : real(0);
            const real leaf_cost = options_.intersection_cost * tests(n);
            if (n <= options_.max_leaf_size && leaf_cost <= split_cost)
                return leaf(begin, n, box, area);
            const int axis = best.axis;
            const real low = centroids.lo[axis];
            const real scale = real(bin_count_) / (centroids.hi[axis] - low);
            const auto first_right = std::partition(
                items_.begin() + std::ptrdiff_t(begin), items_.begin() + std::ptrdiff_t(end),
                [&](const build_item& item) { return bin_of(item.centroid[axis], low, scale) < best.bin; });
            middle = std::size_t(first_right - items_.begin());
            left_box = best.left;
            right_box = best.right;
        }

        const std::size_t index = nodes.size();
        nodes.emplace_back();
        sah_cost += double(options_.traversal_cost) * double(area);
        binary_child left, right;
        if (spare_threads_ > 0 && n >= parallel_threshold) {
            // the right half sorts its own range of items_ in place
            build_in_parallel(
                items_, left, right, [&] { return build(begin, middle, left_box, depth + 1); },
                [&](binary_builder& b) { return b.build(middle, end, right_box, depth + 1); });
        } else {
            left = build(begin, middle, left_box, depth + 1);
            right = build(middle, end, right_box, depth + 1);
        }
        nodes[index].side[0] = left;
        nodes[index].side[1] = right;
        binary_child inner;
        inner.box = box;
        inner.index = std::uint32_t(index);
        return inner;
    }

private:
    /// Builds a node's left child here (build_left()) and its right child on a
    /// thread of its own with half of the spare threads (build_right(b), b a
    /// builder over `right_items`: items_ itself, or an array of its own), then
    /// joins the arrays as a single thread writes them: the right subtree's
    /// nodes after the left subtree's, and its items after ours when it had
    /// an array of its own. So the tree does not depend on the thread count.
    template <class Left, class Right>
    void build_in_parallel(std::vector<build_item>& right_items, binary_child& left, binary_child& right,
                           const Left& build_left, const Right& build_right)
    {
        const int for_right = spare_threads_ / 2 + spare_threads_ % 2 - 1;
        spare_threads_ -= for_right + 1;
        binary_builder right_builder(right_items, options_, for_right, prims_);
        std::exception_ptr failure;
        std::thread worker([&] {
            try {
                right = build_right(right_builder);
            } catch (...) {
                failure = std::current_exception();
            }
        });
        try {
            left = build_left();
        } catch (...) {
            worker.join();
            throw;
        }
        worker.join();
        if (failure)
            std::rethrow_exception(failure);
        const bool own_items = &right_items != &items_;
        const std::uint32_t node_offset = std::uint32_t(nodes.size());
        const std::uint32_t item_offset = own_items ? std::uint32_t(items_.size()) : 0;
        const auto moved = [&](binary_child& c) { c.index += c.count == 0 ? node_offset : item_offset; };
        for (binary_node& node : right_builder.nodes)
            for (binary_child& side : node.side)
                moved(side);
        moved(right);
        nodes.insert(nodes.end(), right_builder.nodes.begin(), right_builder.nodes.end());
        if (own_items)
            items_.insert(items_.end(), right_items.begin(), right_items.end());
        sah_cost += right_builder.sah_cost;
        spatial_splits += right_builder.spatial_splits;
    }

    /// Below this many primitives a subtree is not worth a thread.
    static constexpr std::size_t parallel_threshold = 4096;

    struct bin {
        aabb box;
        std::size_t count = 0;
    };


    /// The leaf tests that n primitives cost: ceil(n / primitives_per_test)
    /// (the SIMD leaf test handles a block of four triangles at the price of
    /// about one; Embree's SAH counts its triangle4 blocks the same way).
    real tests(std::size_t n) const
    {
        const std::size_t per = std::max<std::size_t>(1, options_.primitives_per_test);
        return real((n + per - 1) / per);
    }

    std::size_t bin_of(real centroid, real low, real scale) const
    {
        const real slot = (centroid - low) * scale;
        return std::min(bin_count_ - 1, std::size_t(slot > 0 ? slot : real(0)));
    }

    split find_split(const build_item* items, std::size_t n, const aabb& centroids)
    {
        real low[3], scale[3];
        for (int axis = 0; axis < 3; ++axis) {
            low[axis] = centroids.lo[axis];
            const real extent = centroids.hi[axis] - low[axis];
            scale[axis] = extent > 0 ? real(bin_count_) / extent : real(0); // 0: all in bin 0, never split
            for (bin& b : bins_[axis])
                b = bin{};
        }
        for (std::size_t i = 0; i < n; ++i) { // one pass, three axes
            const build_item& item = items[i];
            for (int axis = 0; axis < 3; ++axis) {
                bin& b = bins_[axis][bin_of(item.centroid[axis], low[axis], scale[axis])];
                b.box.grow(item.box);
                ++b.count;
            }
        }
        split best;
        for (int axis = 0; axis < 3; ++axis) {
            if (scale[axis] == 0)
                continue;
            const std::vector<bin>& bins = bins_[axis];
            // sweep from the right: right_cost_[s] = A_R N_R for the split before bin s
            aabb accumulated;
            std::size_t on_right = 0;
            for (std::size_t s = bin_count_ - 1; s > 0; --s) {
                accumulated.grow(bins[s].box);
                on_right += bins[s].count;
                right_box_[s] = accumulated;
                right_cost_[s] = half_area(accumulated) * tests(on_right);
            }
            aabb left;
            std::size_t on_left = 0;
            for (std::size_t s = 1; s < bin_count_; ++s) {
                left.grow(bins[s - 1].box);
                on_left += bins[s - 1].count;
                if (on_left == 0 || on_left == n)
                    continue;
                const real cost = half_area(left) * tests(on_left) + right_cost_[s];
                if (best.axis < 0 || cost < best.cost) {
                    best.axis = axis;
                    best.bin = s;
                    best.cost = cost;
                    best.left = left;
                    best.right = right_box_[s];
                }
            }
        }
        return best;
    }

    struct spatial_split {
        int axis = -1;
        real plane = 0;
        real cost = 0;          ///< A_L N_L + A_R N_R, as split::cost
        std::size_t extra = 0;  ///< references that would go to both sides
    };

    /// The best plane between `bins` equal slices of the node's box, on any
    /// axis, with each reference's parts binned where they lie ("chopped
    /// binning", Stich et al. sec. 4): a reference spanning several slices
    /// adds the box of its part in each slice (clipped_box) and counts as
    /// entering its first slice and leaving its last.
    /// Axes where no reference is wider than a slice (wide[axis] false) are
    /// skipped: there a plane cuts next to nothing, and an object split
    /// does as well.
    spatial_split find_spatial_split(const std::vector<build_item>& refs, const aabb& box, const bool wide[3])
    {
        spatial_split best;
        const std::size_t count = bin_count_;
        std::vector<aabb> slice(count), right_box(count);
        std::vector<std::size_t> enter(count), leave(count), right_count(count);
        for (int axis = 0; axis < 3; ++axis) {
            const real low = box.lo[axis], extent = box.hi[axis] - box.lo[axis];
            if (!wide[axis] || !(extent > 0))
                continue;
            const real scale = real(count) / extent;
            const auto plane = [&](std::size_t b) { return low + extent * real(b) / real(count); };
            const auto slot = [&](real x) {
                const real at = (x - low) * scale;
                return std::min(count - 1, std::size_t(at > 0 ? at : real(0)));
            };
            std::fill(slice.begin(), slice.end(), aabb{});
            std::fill(enter.begin(), enter.end(), 0);
            std::fill(leave.begin(), leave.end(), 0);
            for (const build_item& r : refs) {
                const std::size_t first = slot(r.box.lo[axis]), last = slot(r.box.hi[axis]);
                ++enter[first];
                ++leave[last];
                if (first == last) {
                    slice[first].grow(r.box);
                    continue;
                }
                const packed_primitive& p = prims_[r.index];
                if (p.id & sphere_flag) { // the slab of the box
                    for (std::size_t b = first; b <= last; ++b) {
                        aabb part = r.box;
                        part.lo[axis] = std::max(part.lo[axis], plane(b));
                        part.hi[axis] = std::min(part.hi[axis], plane(b + 1));
                        slice[b].grow(part);
                    }
                    continue;
                }
                // An estimate, for the cost only (the partition uses
                // clipped_box): each corner goes to its slice and each point
                // where an edge crosses a plane to the slices on both sides,
                // all held inside the reference's box.
                const auto held = [&](const vec3& q) { return glm::clamp(q, r.box.lo, r.box.hi); };
                for (int i = 0; i < 3; ++i) {
                    const vec3 u(p.v[3 * i], p.v[3 * i + 1], p.v[3 * i + 2]);
                    slice[std::max(first, std::min(last, slot(u[axis])))].grow(held(u));
                    const int j = (i + 1) % 3;
                    vec3 a = u, b(p.v[3 * j], p.v[3 * j + 1], p.v[3 * j + 2]);
                    if (a[axis] > b[axis])
                        std::swap(a, b);
                    const std::size_t from = std::max(first, slot(a[axis])), to = std::min(last, slot(b[axis]));
                    for (std::size_t k = from + 1; k <= to; ++k) {
                        const real s = plane(k);
                        const vec3 q = held(a + (b - a) * ((s - a[axis]) / (b[axis] - a[axis])));
                        slice[k - 1].grow(q);
                        slice[k].grow(q);
                    }
                }
            }
            aabb accumulated;
            std::size_t on_right = 0;
            for (std::size_t b = count - 1; b > 0; --b) {
                accumulated.grow(slice[b]);
                on_right += leave[b];
                right_box[b] = accumulated;
                right_count[b] = on_right;
            }
            aabb left;
            std::size_t on_left = 0;
            for (std::size_t b = 1; b < count; ++b) {
                left.grow(slice[b - 1]);
                on_left += enter[b - 1];
                if (on_left == 0 || right_count[b] == 0)
                    continue;
                const real cost = half_area(left) * tests(on_left) + half_area(right_box[b]) * tests(right_count[b]);
                if (best.axis < 0 || cost < best.cost) {
                    best.axis = axis;
                    best.plane = plane(b);
                    best.cost = cost;
                    best.extra = on_left + right_count[b] - refs.size();
                }
            }
        }
        return best;
    }

    binary_child leaf(std::size_t begin, std::size_t n, const aabb& box, real area)
    {
        // two pieces of one primitive (spatial splits) in one leaf: keep one;
        // the rest of the range stays in items_, referenced by no leaf
        const auto first = items_.begin() + std::ptrdiff_t(begin);
        std::sort(first, first + std::ptrdiff_t(n),
                  [](const build_item& x, const build_item& y) { return x.index < y.index; });
        n = std::size_t(std::unique(first, first + std::ptrdiff_t(n),
                                    [](const build_item& x, const build_item& y) { return x.index == y.index; }) -
                        first);
        sah_cost += double(options_.intersection_cost) * double(area) * double(tests(n));
        binary_child c;
        c.box = box;
        c.index = std::uint32_t(begin);
        c.count = std::uint32_t(n);
        return c;
    }

    std::vector<build_item>& items_;
    const bvh_options& options_;
    int spare_threads_;
    const packed_primitive* prims_; ///< for clipped_box (spatial splits only)
    std::size_t bin_count_;
    std::vector<bin> bins_[3];
    std::vector<real> right_cost_;
    std::vector<aabb> right_box_;
};

/// Turns the binary tree into 4-wide nodes (4-wide BVHs for single rays:
/// Wald, Benthin, Boulos, "Getting Rid of Packets", IEEE Symposium on
/// Interactive Ray Tracing 2008; Dammertz, Hanika, Keller, "Shallow Bounding
/// Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR
/// 2008): a node takes its two binary children, then repeatedly replaces its
/// inner child of largest surface area (the one most rays enter) by that
/// child's two children, until it has four. Nodes come out depth first.
class wide_collapser {
public:
    wide_collapser(const std::vector<binary_node>& binary, std::vector<bvh_node>& nodes, bvh_stats& stats)
        : binary_(binary), nodes_(nodes), stats_(stats)
    {
    }

    std::uint32_t collapse(const binary_child& root, int depth)
    {
        binary_child children[4];
        int used = 0;
        if (root.count != 0) { // the whole tree is one leaf
            children[used++] = root;
        } else {
            children[used++] = binary_[root.index].side[0];
            children[used++] = binary_[root.index].side[1];
        }
        while (used < 4) {
            int widest = -1;
            for (int c = 0; c < used; ++c)
                if (children[c].count == 0 &&
                    (widest < 0 || half_area(children[c].box) > half_area(children[widest].box)))
                    widest = c;
            if (widest < 0)
                break;
            const binary_node& opened = binary_[children[widest].index];
            children[widest] = opened.side[0];
            children[used++] = opened.side[1];
        }
        const std::uint32_t index = std::uint32_t(nodes_.size());
        nodes_.emplace_back();
        for (int c = 0; c < 4; ++c) {
            const aabb box = c < used ? children[c].box : aabb{};
            bvh_node& node = nodes_[index];
            for (int k = 0; k < 3; ++k) {
                node.bounds[2 * k][c] = box.lo[k];
                node.bounds[2 * k + 1][c] = box.hi[k];
            }
            node.child[c] = leaf_flag;
            node.count[c] = 0;
        }
        for (int c = 0; c < used; ++c) {
            if (children[c].count != 0) {
                nodes_[index].child[c] = leaf_flag | children[c].index;
                nodes_[index].count[c] = children[c].count;
                ++stats_.leaves;
                stats_.depth = std::max(stats_.depth, depth + 1);
            } else {
                const std::uint32_t below = collapse(children[c], depth + 1);
                nodes_[index].child[c] = below;
            }
        }
        return index;
    }

private:
    const std::vector<binary_node>& binary_;
    std::vector<bvh_node>& nodes_;
    bvh_stats& stats_;
};

#if RT_BVH_SSE
constexpr bool bvh_uses_sse = true;
#else
constexpr bool bvh_uses_sse = false;
#endif

/// The ray as the node test reads it (see the top of this file).
struct node_ray {
    real origin[3];
    real inv_dir[3];
    int near_row[3];  ///< per axis, the row of bvh_node::bounds met first: 2 k (lo) or 2 k + 1 (hi)
    int far_row[3];
#if RT_BVH_SSE
    __m128 origin4[3];   ///< the origin's k-th coordinate in all four lanes
    __m128 inv_dir4[3];  ///< 1/d_k in all four lanes
#endif
};

inline node_ray make_node_ray(const ray& r)
{
    const box_ray b = make_box_ray(r);
    node_ray n;
    for (int k = 0; k < 3; ++k) {
        n.origin[k] = b.origin[k];
        n.inv_dir[k] = b.inv_dir[k];
        n.near_row[k] = 2 * k + b.negative[k];
        n.far_row[k] = 2 * k + 1 - b.negative[k];
#if RT_BVH_SSE
        n.origin4[k] = _mm_set1_ps(float(b.origin[k]));
        n.inv_dir4[k] = _mm_set1_ps(float(b.inv_dir[k]));
#endif
    }
    return n;
}

/// The slab test of hit_box for the four children of `node` at once: bit c of
/// the result is set when child c is met in [tmin, tmax], and tnear[c] is then
/// where the ray enters it. One value at a time.
inline int intersect_children_scalar(const bvh_node& node, const node_ray& r, real tmin, real tmax, real tnear[4])
{
    int mask = 0;
    for (int c = 0; c < 4; ++c) {
        real t0 = tmin, t1 = tmax;
        for (int k = 0; k < 3; ++k) {
            const real t_near = (node.bounds[r.near_row[k]][c] - r.origin[k]) * r.inv_dir[k];
            const real t_far = (node.bounds[r.far_row[k]][c] - r.origin[k]) * r.inv_dir[k];
            t0 = t_near > t0 ? t_near : t0; // a NaN keeps the interval (see hit_box)
            t1 = t_far < t1 ? t_far : t1;
        }
        tnear[c] = t0;
        mask |= (t0 <= t1 * slab_far_factor ? 1 : 0) << c;
    }
    return mask;
}

#if RT_BVH_SSE
/// The same test with SSE, one child per lane. _mm_max_ps(a, b) is exactly
/// a > b ? a : b and _mm_min_ps(a, b) is a < b ? a : b, NaN included, so every
/// lane computes bit for bit what intersect_children_scalar computes.
inline int intersect_children_sse(const bvh_node& node, const node_ray& r, float tmin, float tmax, float tnear[4])
{
    // the three axes written out: the compiler keeps every value in a register
    const __m128 near_x = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[0]]), r.origin4[0]), r.inv_dir4[0]);
    const __m128 far_x = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[0]]), r.origin4[0]), r.inv_dir4[0]);
    const __m128 near_y = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[1]]), r.origin4[1]), r.inv_dir4[1]);
    const __m128 far_y = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[1]]), r.origin4[1]), r.inv_dir4[1]);
    const __m128 near_z = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[2]]), r.origin4[2]), r.inv_dir4[2]);
    const __m128 far_z = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[2]]), r.origin4[2]), r.inv_dir4[2]);
    const __m128 t0 = _mm_max_ps(near_z, _mm_max_ps(near_y, _mm_max_ps(near_x, _mm_set1_ps(tmin))));
    const __m128 t1 = _mm_min_ps(far_z, _mm_min_ps(far_y, _mm_min_ps(far_x, _mm_set1_ps(tmax))));
    _mm_storeu_ps(tnear, t0);
    return _mm_movemask_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(float(slab_far_factor)))));
}
#endif

inline int intersect_children(const bvh_node& node, const node_ray& r, real tmin, real tmax, real tnear[4])
{
#if RT_BVH_SSE
    return intersect_children_sse(node, r, tmin, tmax, tnear);
#else
    return intersect_children_scalar(node, r, tmin, tmax, tnear);
#endif
}

/// The lowest set bit of a 4-bit mask (lowest_bit[0] is 0, never used).
constexpr int lowest_bit[16] = {0, 0, 1, 0, 2, 0, 1, 0, 3, 0, 1, 0, 2, 0, 1, 0};

/// The children met by a ray, nearest first, without a branch (closest hit,
/// see the top of this file): order[0 .. n-1] are the lanes of `mask` by
/// increasing tnear, order[n .. 3] the others; returns n, the number met.
///
/// Each lane gets a key, the bits of its tnear as an integer with the lane
/// number in the two lowest bits (a lane not met gets the largest key). For
/// floats >= 0 the integer order is the float order, and the lane bits make
/// the keys distinct, so a lane's rank (how many keys are smaller) is a
/// permutation of 0 ... 3; order[rank] = lane. Dropping two bits of tnear may
/// reorder children whose entry distances are within 3 ulps, which changes
/// no result: the closest hit is decided by replaces(), not by the order of
/// the visits. (With a negative tmin a negative tnear sorts first: the order
/// is then only approximate, and the result again the same.)
inline int order_children(int mask, const real tnear[4], int order[4])
{
#if RT_BVH_SSE
    const __m128i lane = _mm_set_epi32(3, 2, 1, 0);
    const __m128i bit = _mm_set_epi32(8, 4, 2, 1);
    const __m128i met = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(mask), bit), bit);
    const __m128i t = _mm_castps_si128(_mm_loadu_ps(tnear));
    const __m128i bits = _mm_or_si128(_mm_and_si128(met, t), _mm_andnot_si128(met, _mm_set1_epi32(0x7fffffff)));
    const __m128i keys = _mm_andnot_si128(_mm_set1_epi32(3), bits); // the two low bits cleared
    const __m128i k = _mm_or_si128(keys, lane);
    // rank = how many of the other three keys are smaller: compare with the
    // keys rotated by one, two and three lanes (cmpgt gives -1 where true)
    const __m128i r1 = _mm_cmpgt_epi32(k, _mm_shuffle_epi32(k, _MM_SHUFFLE(0, 3, 2, 1)));
    const __m128i r2 = _mm_cmpgt_epi32(k, _mm_shuffle_epi32(k, _MM_SHUFFLE(1, 0, 3, 2)));
    const __m128i r3 = _mm_cmpgt_epi32(k, _mm_shuffle_epi32(k, _MM_SHUFFLE(2, 1, 0, 3)));
    const __m128i rank = _mm_sub_epi32(_mm_setzero_si128(), _mm_add_epi32(_mm_add_epi32(r1, r2), r3));
    alignas(16) std::int32_t ranks[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(ranks), rank);
#else
    std::int32_t keys[4], ranks[4];
    for (int c = 0; c < 4; ++c) {
        std::uint32_t bits = 0x7fffffffu;
        if (mask & (1 << c)) {
            const float t = float(tnear[c]);
            std::memcpy(&bits, &t, sizeof bits);
        }
        bits = (bits & ~3u) | std::uint32_t(c);
        keys[c] = std::int32_t(bits);
    }
    for (int c = 0; c < 4; ++c)
        ranks[c] = (keys[(c + 1) & 3] < keys[c]) + (keys[(c + 2) & 3] < keys[c]) + (keys[(c + 3) & 3] < keys[c]);
#endif
    for (int c = 0; c < 4; ++c)
        order[ranks[c]] = c;
    static constexpr int bits_set[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    return bits_set[mask & 15];
}

/// The ray as the leaf test reads it: the watertight test's permutation as
/// rows of triangle_block::v (row_x[i] = 3 i + kx: corner i's kx coordinate)
/// and, with SSE, the origin and the shear in all four lanes.
struct leaf_ray {
    int row_x[3], row_y[3], row_z[3];
#if RT_BVH_SSE
    __m128 px, py, pz;  ///< p_kx, p_ky, p_kz
    __m128 Sx, Sy, Sz;
#endif
};

inline leaf_ray make_leaf_ray(const watertight_ray& w)
{
    leaf_ray r;
    for (int i = 0; i < 3; ++i) {
        r.row_x[i] = 3 * i + w.kx;
        r.row_y[i] = 3 * i + w.ky;
        r.row_z[i] = 3 * i + w.kz;
    }
#if RT_BVH_SSE
    r.px = _mm_set1_ps(float(w.p[w.kx]));
    r.py = _mm_set1_ps(float(w.p[w.ky]));
    r.pz = _mm_set1_ps(float(w.p[w.kz]));
    r.Sx = _mm_set1_ps(float(w.Sx));
    r.Sy = _mm_set1_ps(float(w.Sy));
    r.Sz = _mm_set1_ps(float(w.Sz));
#endif
    return r;
}

/// The watertight test of the triangles of block `b`, one lane at a time:
/// each lane's corners are gathered and handed to intersect_watertight. Bit l
/// of the result is set when lane l is hit in [tmin, tmax], and hits[l] is
/// then its hit. Sphere lanes are left to the caller. The fallback where SSE
/// is missing, and the reference the tests compare intersect_block_sse with.
inline int intersect_block_scalar(const triangle_block& b, const watertight_ray& w, real tmin, real tmax,
                                  triangle_hit hits[4])
{
    int mask = 0;
    for (int lane = 0; lane < 4; ++lane) {
        if (b.id[lane] & sphere_flag)
            continue;
        real v[9];
        for (int j = 0; j < 9; ++j)
            v[j] = b.v[j][lane];
        if (intersect_watertight(w, v, tmin, tmax, hits[lane])) // NaN (unused) lanes miss
            mask |= 1 << lane;
    }
    return mask;
}

/// The lanes of `b` that hold spheres (bit l for lane l).
inline int sphere_lanes(const triangle_block& b)
{
#if RT_BVH_SSE
    return _mm_movemask_ps(_mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(b.id))));
#else
    int mask = 0;
    for (int lane = 0; lane < 4; ++lane)
        mask |= (b.id[lane] & sphere_flag) ? 1 << lane : 0;
    return mask;
#endif
}

#if RT_BVH_SSE
/// Four floats widened to double: one AVX register, or two SSE2 registers
/// (the low pair, then the high pair). Each sheared coordinate is widened once
/// and serves two edge functions.
struct wide4 {
#if RT_BVH_AVX
    __m256d all;
#else
    __m128d lo, hi;
#endif
};

inline wide4 widen(__m128 a)
{
#if RT_BVH_AVX
    return wide4{_mm256_cvtps_pd(a)};
#else
    return wide4{_mm_cvtps_pd(a), _mm_cvtps_pd(_mm_movehl_ps(a, a))};
#endif
}

/// a b - c d for four lanes, each product and the difference in double, the
/// result rounded to float: what intersect_watertight computes for one edge
/// function, lane by lane, bit for bit (a product of two floats is exact in
/// double, and the difference is rounded to double then to float in both).
inline __m128 edge_function4(const wide4& a, const wide4& b, const wide4& c, const wide4& d)
{
#if RT_BVH_AVX
    return _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_mul_pd(a.all, b.all), _mm256_mul_pd(c.all, d.all)));
#else
    const __m128d lo = _mm_sub_pd(_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(c.lo, d.lo));
    const __m128d hi = _mm_sub_pd(_mm_mul_pd(a.hi, b.hi), _mm_mul_pd(c.hi, d.hi));
    return _mm_movelh_ps(_mm_cvtpd_ps(lo), _mm_cvtpd_ps(hi));
#endif
}

/// max_abs3 (watertight.hpp) of four lanes: the largest of |p|, |q|, |s|.
inline __m128 max_abs3_sse(__m128 p, __m128 q, __m128 s)
{
    const __m128 sign = _mm_set1_ps(-0.0f);
    return _mm_max_ps(_mm_max_ps(_mm_andnot_ps(sign, p), _mm_andnot_ps(sign, q)), _mm_andnot_ps(sign, s));
}

/// The watertight test of four triangles at once, one per lane: the same
/// arithmetic as intersect_watertight and watertight_finish (translation,
/// shear, edge functions in double, the sign test, det, T, t, the range, the
/// distance check of watertight_t_error and the barycentrics), operation for
/// operation in the same order, so each lane computes the same bits and
/// intersect_block_scalar gives the same result (tests/stage04_triangle.cpp
/// checks it on rays through shared edges and vertices). Only a lane whose t is
/// within its error bound leaves SIMD, for t_beyond_error_in_double. Needs
/// -ffp-contract=off on FMA targets, as the scalar test does: a fused
/// multiply-add would round the shear differently here and there.
inline int intersect_block_sse(const triangle_block& b, const leaf_ray& r, const watertight_ray& w, float tmin,
                               float tmax, triangle_hit hits[4])
{
    const __m128 zero = _mm_setzero_ps();
    // corners translated to the origin and permuted: x (kx), y (ky), z (kz)
    const __m128 ax = _mm_sub_ps(_mm_load_ps(b.v[r.row_x[0]]), r.px);
    const __m128 bx = _mm_sub_ps(_mm_load_ps(b.v[r.row_x[1]]), r.px);
    const __m128 cx = _mm_sub_ps(_mm_load_ps(b.v[r.row_x[2]]), r.px);
    const __m128 ay = _mm_sub_ps(_mm_load_ps(b.v[r.row_y[0]]), r.py);
    const __m128 by = _mm_sub_ps(_mm_load_ps(b.v[r.row_y[1]]), r.py);
    const __m128 cy = _mm_sub_ps(_mm_load_ps(b.v[r.row_y[2]]), r.py);
    const __m128 az = _mm_sub_ps(_mm_load_ps(b.v[r.row_z[0]]), r.pz);
    const __m128 bz = _mm_sub_ps(_mm_load_ps(b.v[r.row_z[1]]), r.pz);
    const __m128 cz = _mm_sub_ps(_mm_load_ps(b.v[r.row_z[2]]), r.pz);
    // sheared
    const __m128 Ax = _mm_sub_ps(ax, _mm_mul_ps(r.Sx, az));
    const __m128 Ay = _mm_sub_ps(ay, _mm_mul_ps(r.Sy, az));
    const __m128 Bx = _mm_sub_ps(bx, _mm_mul_ps(r.Sx, bz));
    const __m128 By = _mm_sub_ps(by, _mm_mul_ps(r.Sy, bz));
    const __m128 Cx = _mm_sub_ps(cx, _mm_mul_ps(r.Sx, cz));
    const __m128 Cy = _mm_sub_ps(cy, _mm_mul_ps(r.Sy, cz));
    // edge functions, and the sign test: a miss when some are < 0 and some > 0
    const wide4 Ax2 = widen(Ax), Ay2 = widen(Ay), Bx2 = widen(Bx), By2 = widen(By), Cx2 = widen(Cx), Cy2 = widen(Cy);
    const __m128 U = edge_function4(Cx2, By2, Cy2, Bx2);
    const __m128 V = edge_function4(Ax2, Cy2, Ay2, Cx2);
    const __m128 W = edge_function4(Bx2, Ay2, By2, Ax2);
    const __m128 negative = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(U, zero), _mm_cmplt_ps(V, zero)), _mm_cmplt_ps(W, zero));
    const __m128 positive = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(U, zero), _mm_cmpgt_ps(V, zero)), _mm_cmpgt_ps(W, zero));
    int mask = ~_mm_movemask_ps(_mm_and_ps(negative, positive)) & 15;
    if (mask == 0)
        return 0;
    // det, T and t as watertight_finish computes them; t in [tmin, tmax] (a
    // NaN fails both comparisons: unused and sphere lanes end here) and det != 0
    const __m128 det = _mm_add_ps(_mm_add_ps(U, V), W);
    const __m128 Az = _mm_mul_ps(r.Sz, az), Bz = _mm_mul_ps(r.Sz, bz), Cz = _mm_mul_ps(r.Sz, cz);
    const __m128 T = _mm_add_ps(_mm_add_ps(_mm_mul_ps(U, Az), _mm_mul_ps(V, Bz)), _mm_mul_ps(W, Cz));
    const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
    const __m128 t = _mm_mul_ps(T, inv_det);
    const __m128 in_range = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(t, _mm_set1_ps(tmin)), _mm_cmple_ps(t, _mm_set1_ps(tmax))),
                                       _mm_cmpneq_ps(det, zero));
    mask &= _mm_movemask_ps(in_range);
    if (mask == 0)
        return 0;
    // the distance check, watertight_t_error<float> lane by lane, the same
    // operations in the same order (_mm_max_ps(a, b) is a > b ? a : b, as in
    // max_abs3; the absolute value clears the sign bit, as std::fabs)
    const __m128 sign = _mm_set1_ps(-0.0f);
    const __m128 max_x = max_abs3_sse(ax, bx, cx), max_y = max_abs3_sse(ay, by, cy), max_z = max_abs3_sse(az, bz, cz);
    const __m128 max_X = max_abs3_sse(Ax, Bx, Cx), max_Y = max_abs3_sse(Ay, By, Cy), max_Z = max_abs3_sse(Az, Bz, Cz);
    const __m128 max_E = max_abs3_sse(U, V, W);
    const __m128 gamma2 = _mm_set1_ps(gamma_in<float>(2)), gamma3 = _mm_set1_ps(gamma_in<float>(3));
    const __m128 gamma5 = _mm_set1_ps(gamma_in<float>(5));
    const __m128 delta_x = _mm_mul_ps(gamma5, _mm_add_ps(max_x, max_z));
    const __m128 delta_y = _mm_mul_ps(gamma5, _mm_add_ps(max_y, max_z));
    const __m128 delta_z = _mm_mul_ps(gamma3, max_Z);
    const __m128 delta_e = _mm_mul_ps(
        _mm_set1_ps(2.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(gamma2, max_X), max_Y), _mm_mul_ps(delta_y, max_X)),
                                      _mm_mul_ps(delta_x, max_Y)));
    const __m128 bound = _mm_mul_ps(
        _mm_mul_ps(_mm_set1_ps(3.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(gamma3, max_E), max_Z),
                                                            _mm_mul_ps(delta_e, max_Z)),
                                                 _mm_mul_ps(delta_z, max_E))),
        _mm_andnot_ps(sign, inv_det));
    const int beyond = _mm_movemask_ps(_mm_cmpgt_ps(t, bound));
    // the lanes within their bound get the second opinion in double (rare)
    for (int doubtful = mask & ~beyond, lane = 0; doubtful != 0; ++lane, doubtful >>= 1)
        if ((doubtful & 1) && !t_beyond_error_in_double(w, &b.v[0][lane], 4))
            mask &= ~(1 << lane);
    if (mask == 0)
        return 0;
    alignas(16) float out[4][4];
    _mm_store_ps(out[0], t);
    _mm_store_ps(out[1], _mm_mul_ps(U, inv_det));
    _mm_store_ps(out[2], _mm_mul_ps(V, inv_det));
    _mm_store_ps(out[3], _mm_mul_ps(W, inv_det));
    for (int lane = 0; lane < 4; ++lane)
        if (mask & (1 << lane)) {
            hits[lane].t = out[0][lane];
            hits[lane].b0 = out[1][lane];
            hits[lane].b1 = out[2][lane];
            hits[lane].b2 = out[3][lane];
        }
    return mask;
}
#endif

/// The leaf test of bvh traversal: intersect_block_sse where SSE is there,
/// else intersect_block_scalar. Both give the same bits.
inline int intersect_block(const triangle_block& b, const leaf_ray& r, const watertight_ray& w, real tmin, real tmax,
                           triangle_hit hits[4])
{
#if RT_BVH_SSE
    return intersect_block_sse(b, r, w, tmin, tmax, hits);
#else
    (void)r;
    return intersect_block_scalar(b, w, tmin, tmax, hits);
#endif
}

} // namespace detail

/// A BVH over packed primitives (see the top of this file). Built once; its
/// queries are const and safe to run from many threads at once.
class bvh {
public:
    bvh() = default;

    /// Builds the hierarchy; the primitives are reordered into leaf order.
    explicit bvh(std::vector<packed_primitive> prims, const bvh_options& options = {})
        : prims_(std::move(prims))
    {
        stats_.primitives = prims_.size();
        if (prims_.empty())
            return;
        if (prims_.size() >= std::size_t(leaf_flag))
            throw error("expected at most 2^31 - 1 primitives in one BVH, found " + std::to_string(prims_.size()));
        bvh_options used = options;
        used.max_depth = std::max(1, std::min(used.max_depth, max_depth));
        used.max_leaf_size = std::max<std::size_t>(1, used.max_leaf_size);

        std::vector<detail::build_item> items(prims_.size());
        aabb scene_box;
        for (std::size_t i = 0; i < prims_.size(); ++i) {
            items[i].box = packed_bounds(prims_[i]);
            items[i].centroid = items[i].box.center();
            items[i].index = std::uint32_t(i);
            scene_box.grow(items[i].box);
        }
        const int threads = used.threads > 0 ? used.threads : int(std::max(1u, std::thread::hardware_concurrency()));
        detail::binary_builder builder(items, used, threads - 1, prims_.data());
        builder.nodes.reserve(prims_.size());
        std::size_t budget = std::size_t(std::max(real(0), used.spatial_budget) * real(prims_.size()));
        detail::binary_child root;
        if (budget > 0) {
            std::vector<detail::build_item> refs;
            refs.swap(items);
            items.reserve(refs.size() + budget);
            root = builder.build_spatial(std::move(refs), scene_box, 0, detail::half_area(scene_box), budget);
        } else {
            root = builder.build(0, items.size(), scene_box, 0);
        }
        stats_.references = items.size();
        stats_.spatial_splits = builder.spatial_splits;
        const std::vector<detail::binary_node>& binary = builder.nodes;
        const real root_area = detail::half_area(scene_box);
        stats_.sah_cost = root_area > 0 ? builder.sah_cost / double(root_area) : 0;
        stats_.binary_nodes = binary.size();

        nodes_.reserve(binary.size() / 2 + 1);
        detail::wide_collapser(binary, nodes_, stats_).collapse(root, 0);
        stats_.nodes = nodes_.size();

        std::vector<packed_primitive> ordered(items.size());
        for (std::size_t i = 0; i < items.size(); ++i) {
            ordered[i] = prims_[items[i].index];
            has_spheres_ = has_spheres_ || (ordered[i].id & sphere_flag) != 0;
        }
        prims_ = std::move(ordered);

        // each leaf's primitives as blocks of four, in the order the nodes
        // meet the leaves (depth first); the leaf's reference becomes its
        // first block, count stays its number of primitives
        blocks_.reserve(prims_.size() / 2 + 1);
        for (bvh_node& node : nodes_)
            for (int c = 0; c < 4; ++c) {
                if (!(node.child[c] & leaf_flag) || node.count[c] == 0)
                    continue;
                const std::size_t first = node.child[c] & ~leaf_flag;
                node.child[c] = leaf_flag | std::uint32_t(blocks_.size());
                for (std::size_t done = 0; done < node.count[c]; done += 4)
                    blocks_.push_back(pack_triangle_block(prims_.data(), first + done,
                                                          std::min<std::size_t>(4, node.count[c] - done)));
            }
    }

    /// The closest hit in [tmin, tmax] by replaces(), or false.
    bool closest(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        return traverse<false, false>(r, tmin, tmax, best);
    }

    /// Whether anything is hit in [tmin, tmax]; stops at the first hit found.
    bool any(const ray& r, real tmin, real tmax) const
    {
        primitive_hit unused;
        return traverse<true, false>(r, tmin, tmax, unused);
    }

    /// closest() with the node and leaf tests done one value at a time (the
    /// fallback where SSE is missing), for the tests to compare with closest().
    bool closest_scalar(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        return traverse<false, true>(r, tmin, tmax, best);
    }

    /// any() one value at a time, as closest_scalar.
    bool any_scalar(const ray& r, real tmin, real tmax) const
    {
        primitive_hit unused;
        return traverse<true, true>(r, tmin, tmax, unused);
    }

    const std::vector<bvh_node>& nodes() const { return nodes_; }
    /// The references in build order (bvh_stats::references of them): each
    /// primitive, once per piece where spatial splits cut it.
    const std::vector<packed_primitive>& primitives() const { return prims_; }
    /// The leaves' primitives as blocks of four (a leaf's reference in
    /// bvh_node::child is leaf_flag | its first block).
    const std::vector<triangle_block>& blocks() const { return blocks_; }
    const bvh_stats& stats() const { return stats_; }

    /// Whether the node test runs in SSE registers (x86-64 and rt::real = float).
    static constexpr bool uses_sse = detail::bvh_uses_sse;

    /// The deepest binary tree built; a 4-wide node pushes at most 3 children,
    /// so the traversal stack needs 3 entries per level.
    static constexpr int max_depth = 60;
    static constexpr int stack_size = 3 * max_depth + 4;

private:
    /// A child waiting on the traversal stack, with the distance where the ray enters it.
    struct entry {
        std::uint32_t child, count;
        real tnear;
    };

    /// The children met (bit c of `mask`, known at compile time) of `node`:
    /// enter one, push the others. Any hit: the first met is entered and the
    /// others pushed unsorted, since any hit ends the search whatever the
    /// order (sorting them made shadow rays 1.6x slower on the bunny:
    /// docs/performance.md). Closest hit: nearest first; one child is entered,
    /// two are ordered by a select, not a branch (their order is a coin toss on
    /// incoherent rays), three or four are ranked by order_children, without a
    /// branch either: three entries are always written and top moves past the
    /// n - 1 met.
    template <int mask, bool any_hit>
    static void descend(const bvh_node& node, const real tnear[4], entry* stack, int& top, std::uint32_t& child,
                        std::uint32_t& count)
    {
        constexpr int first = detail::lowest_bit[mask];
        constexpr int rest = mask & (mask - 1);
        if constexpr (rest == 0) {
            child = node.child[first];
            count = node.count[first];
        } else if constexpr (any_hit) {
            for (int c = 0; c < 4; ++c)
                if (c != first && (mask & (1 << c)))
                    stack[top++] = entry{node.child[c], node.count[c], tnear[c]};
            child = node.child[first];
            count = node.count[first];
        } else if constexpr ((rest & (rest - 1)) == 0) {
            constexpr int second = detail::lowest_bit[rest];
            const bool swap = tnear[second] < tnear[first];
            const int near_child = swap ? second : first, far_child = swap ? first : second;
            stack[top++] = entry{node.child[far_child], node.count[far_child], tnear[far_child]};
            child = node.child[near_child];
            count = node.count[near_child];
        } else {
            int order[4];
            const int n = detail::order_children(mask, tnear, order);
            for (int i = 3; i > 0; --i) {
                const int c = order[i];
                stack[top] = entry{node.child[c], node.count[c], tnear[c]};
                top += i < n ? 1 : 0;
            }
            child = node.child[order[0]];
            count = node.count[order[0]];
        }
    }

    template <bool any_hit, bool scalar>
    bool traverse(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        if (nodes_.empty())
            return false;
        const detail::node_ray nr = detail::make_node_ray(r);
        const watertight_ray wr = make_watertight_ray(r);
        const detail::leaf_ray lr = detail::make_leaf_ray(wr);
        entry stack[stack_size];
        int top = 0;
        bool found = false;
        real closest_t = tmax; // a hit must have t <= closest_t: tmax, then the closest hit so far
        std::uint32_t child = 0, count = 0; // the root
        for (;;) {
            if (!(child & leaf_flag)) {
                const bvh_node& node = nodes_[child];
                real tnear[4];
                const int mask = scalar ? detail::intersect_children_scalar(node, nr, tmin, closest_t, tnear)
                                        : detail::intersect_children(node, nr, tmin, closest_t, tnear);
                // One indirect branch on the mask (a jump table): each case
                // knows at compile time which children it enters, so on
                // coherent rays, where the branch is predicted, the processor
                // starts loading the next node before the box test is done,
                // and on incoherent rays a visit costs at most one misprediction.
                switch (mask) {
                case 0: break;
                case 1: descend<1, any_hit>(node, tnear, stack, top, child, count); continue;
                case 2: descend<2, any_hit>(node, tnear, stack, top, child, count); continue;
                case 3: descend<3, any_hit>(node, tnear, stack, top, child, count); continue;
                case 4: descend<4, any_hit>(node, tnear, stack, top, child, count); continue;
                case 5: descend<5, any_hit>(node, tnear, stack, top, child, count); continue;
                case 6: descend<6, any_hit>(node, tnear, stack, top, child, count); continue;
                case 7: descend<7, any_hit>(node, tnear, stack, top, child, count); continue;
                case 8: descend<8, any_hit>(node, tnear, stack, top, child, count); continue;
                case 9: descend<9, any_hit>(node, tnear, stack, top, child, count); continue;
                case 10: descend<10, any_hit>(node, tnear, stack, top, child, count); continue;
                case 11: descend<11, any_hit>(node, tnear, stack, top, child, count); continue;
                case 12: descend<12, any_hit>(node, tnear, stack, top, child, count); continue;
                case 13: descend<13, any_hit>(node, tnear, stack, top, child, count); continue;
                case 14: descend<14, any_hit>(node, tnear, stack, top, child, count); continue;
                default: descend<15, any_hit>(node, tnear, stack, top, child, count); continue;
                }
            } else {
                // a leaf: its blocks of four, each tested at once (see the
                // top of this file); a block's hits are taken by replaces(),
                // so the closest hit does not depend on the order of the lanes
                const triangle_block* block = blocks_.data() + (child & ~leaf_flag);
                for (std::uint32_t done = 0; done < count; done += 4, ++block) {
                    triangle_hit hits[4];
                    int mask = scalar ? detail::intersect_block_scalar(*block, wr, tmin, closest_t, hits)
                                      : detail::intersect_block(*block, lr, wr, tmin, closest_t, hits);
                    if (mask != 0 && any_hit)
                        return true;
                    for (int lane = 0; mask != 0; ++lane, mask >>= 1) {
                        if (!(mask & 1))
                            continue;
                        const primitive_hit h{hits[lane].t, hits[lane].b0, hits[lane].b1, hits[lane].b2,
                                              block->id[lane], &block->v[0][lane], 4};
                        if (!found || replaces(h, best)) {
                            best = h;
                            found = true;
                            closest_t = h.t;
                        }
                    }
                    if (!has_spheres_) // most scenes: no need to look at the ids
                        continue;
                    for (int spheres = detail::sphere_lanes(*block), lane = 0; spheres != 0; ++lane, spheres >>= 1) {
                        if (!(spheres & 1))
                            continue;
                        packed_primitive p{{0, 0, 0, 0, 0, 0, 0, 0, 0}, block->id[lane]};
                        for (int j = 0; j < 4; ++j)
                            p.v[j] = block->v[j][lane];
                        primitive_hit h;
                        if (intersect_packed(p, r, wr, tmin, closest_t, h) && (!found || replaces(h, best))) {
                            best = h;
                            if (any_hit)
                                return true;
                            found = true;
                            closest_t = h.t;
                        }
                    }
                }
            }
            // the next entry on the stack that can still hold a hit at t <= closest_t
            const real cut = closest_t * slab_far_factor;
            for (;;) {
                if (top == 0)
                    return found;
                const entry& e = stack[--top];
                if (e.tnear <= cut) {
                    child = e.child;
                    count = e.count;
                    break;
                }
            }
        }
    }

    std::vector<packed_primitive> prims_;
    std::vector<bvh_node> nodes_;
    std::vector<triangle_block> blocks_;
    bool has_spheres_ = false;
    bvh_stats stats_;
};

} // namespace rt

#undef RT_BVH_SSE
#undef RT_BVH_AVX
