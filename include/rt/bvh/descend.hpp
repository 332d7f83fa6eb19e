// bvh/descend.hpp - which of the children a node test met a ray enters, and
// the order in which the others wait on the traversal stack.
//
//  - Closest hit enters the nearest child first: two are ordered by a select,
//    three or more by ranking their distances in SIMD, without a branch (on
//    incoherent rays the order is a coin toss that a branch would mispredict).
//  - Any hit enters one child and pushes the others unsorted: any hit ends the
//    search whatever the order, and sorting costs shadow rays more than it
//    saves. 4-wide nodes enter the lowest lane met, 8-wide ones the highest
//    (as Embree does), each the better of the two on the shadow sets.
//  - The choice is a jump on the mask of children met whose cases know their
//    children at compile time (all 15 masks of a 4-wide node; the 36 masks of
//    one or two children of an 8-wide node, the rest in SIMD): where the jump
//    is predicted, the next node loads before the box test has finished.
// The measurements are in docs/performance.md, experiment 6.
// (No #pragma once: a unit may compile this file once per width, bvh/dispatch.hpp;
// the guard after the section opens keeps one copy of each.)

#include <cstdint>
#include <cstring>

#include "../core/config.hpp"
#include "layout.hpp"

#include "simd_begin.hpp" // RT_BVH_SSE, RT_BVH_AVX2 and the intrinsics, until simd_end.hpp
#if RT_BVH_AVX512 ? !defined(RT_BVH_DESCEND_W8X) : RT_BVH_AVX2 ? !defined(RT_BVH_DESCEND_W8) : !defined(RT_BVH_DESCEND_W4)
#if RT_BVH_AVX512
#define RT_BVH_DESCEND_W8X
#elif RT_BVH_AVX2
#define RT_BVH_DESCEND_W8
#else
#define RT_BVH_DESCEND_W4
#endif

namespace rt {
namespace detail {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

/// The children waiting during a traversal and the distances where the ray
/// enters them, as three arrays, so the 8-wide descent writes each with one
/// store of eight (up to 8 entries past `capacity` may be written). The
/// count of entries is the traversal's own variable, `top` (kept in a
/// register, not in the arrays' struct).
template <int capacity>
struct traversal_stack {
    alignas(32) std::uint32_t child[capacity + 8];
    alignas(32) std::uint32_t count[capacity + 8];
    alignas(32) real t[capacity + 8];

    void push(int& top, const bvh_node& node, int c, const real tnear[])
    {
        child[top] = node.child[c];
        count[top] = node.count[c];
        t[top] = tnear[c];
        ++top;
    }
};

/// The lowest set bit of a 4-bit mask (lowest_bit[0] is 0, never used).
constexpr int lowest_bit[16] = {0, 0, 1, 0, 2, 0, 1, 0, 3, 0, 1, 0, 2, 0, 1, 0};

/// The children met by a 4-wide node, nearest first, without a branch: order[0 .. n-1] are the lanes of `mask` by
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

/// The children met (bit c of `mask`, known at compile time) of a 4-wide
/// node: enter one, push the others (see the top of this file). Three or
/// four met: three entries are always written and top moves past the n - 1 met.
template <int mask, bool any_hit, class Stack>
RT_BVH_INLINE void descend4(const bvh_node& node, const real tnear[], Stack& stack, int& top, std::uint32_t& child,
                            std::uint32_t& count)
{
    constexpr int first = lowest_bit[mask];
    constexpr int rest = mask & (mask - 1);
    if constexpr (rest == 0) {
        child = node.child[first];
        count = node.count[first];
    } else if constexpr (any_hit) {
        for (int c = 0; c < 4; ++c)
            if (c != first && (mask & (1 << c)))
                stack.push(top, node, c, tnear);
        child = node.child[first];
        count = node.count[first];
    } else if constexpr ((rest & (rest - 1)) == 0) {
        constexpr int second = lowest_bit[rest];
        const bool swap = tnear[second] < tnear[first];
        const int near_child = swap ? second : first, far_child = swap ? first : second;
        stack.push(top, node, far_child, tnear);
        child = node.child[near_child];
        count = node.count[near_child];
    } else {
        int order[4];
        const int n = order_children(mask, tnear, order);
        for (int i = 3; i > 0; --i) {
            stack.push(top, node, order[i], tnear);
            top -= i < n ? 0 : 1;
        }
        child = node.child[order[0]];
        count = node.count[order[0]];
    }
}

#if RT_BVH_AVX2
/// The number of lanes of an 8-bit mask, and its highest (mask not 0).
inline int lane_count8(int mask)
{
    int n = 0;
    for (int m = mask & 255; m != 0; m &= m - 1)
        ++n;
    return n;
}
inline int highest_lane8(int mask)
{
    int c = 7;
    while (!(mask & (1 << c)))
        --c;
    return c;
}

/// For an 8-bit mask: 0 ... 7 for one child (its lane), 8 ... 35 for two
/// (the pairs in order), 36 for three or more.
struct mask_cases {
    unsigned char of[256] = {};
    constexpr mask_cases()
    {
        for (int m = 0; m < 256; ++m)
            of[m] = 36;
        int k = 0;
        for (int a = 0; a < 8; ++a)
            of[1 << a] = static_cast<unsigned char>(k++);
        for (int a = 0; a < 8; ++a)
            for (int b = a + 1; b < 8; ++b)
                of[(1 << a) | (1 << b)] = static_cast<unsigned char>(k++);
    }
};
inline constexpr mask_cases mask_case{};

/// For an 8-bit mask, its lanes in increasing order, then zeros: the
/// permutation that packs the children of the mask to the front of a register.
struct packed_lanes {
    unsigned char of[256][8] = {};
    constexpr packed_lanes()
    {
        for (int m = 0; m < 256; ++m) {
            int j = 0;
            for (int c = 0; c < 8; ++c)
                if (m & (1 << c))
                    of[m][j++] = static_cast<unsigned char>(c);
        }
    }
};
inline constexpr packed_lanes lanes_of{};

/// Two children met, lanes a < b known at compile time: any hit enters b and
/// pushes a; closest hit enters the nearer by a select.
template <int a, int b, bool any_hit, class Stack>
RT_BVH_INLINE void descend_pair(const bvh_node& node, const real tnear[], Stack& stack, int& top, std::uint32_t& child,
                                std::uint32_t& count)
{
    int near_child = b, far_child = a;
    if (!any_hit) {
        const bool swap = tnear[b] < tnear[a];
        near_child = swap ? b : a;
        far_child = swap ? a : b;
    }
    stack.push(top, node, far_child, tnear);
    child = node.child[near_child];
    count = node.count[near_child];
}

/// Three or more children met (`mask`) of an 8-wide node: any hit enters the
/// highest lane and pushes the others packed by one permutation of each
/// array; closest hit ranks the lanes by tnear as order_children does (keys:
/// tnear's bits with the lane in the three low bits; a lane not met gets the
/// largest key), enters rank 0 and pushes ranks n-1 ... 1 with one permuted
/// store per array.
template <bool any_hit, class Stack>
RT_BVH_INLINE void descend_many(int mask, const bvh_node& node, const real tnear[], Stack& stack, int& top,
                                std::uint32_t& child, std::uint32_t& count)
{
    const __m256i children = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.child));
    const __m256i counts = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.count));
    const __m256 t = _mm256_load_ps(tnear);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    int enter = 0, pushed = 0;
    __m256i perm;
    if (any_hit) {
        enter = highest_lane8(mask);
        const int others = mask & ~(1 << enter);
        perm = _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(lanes_of.of[others])));
        pushed = lane_count8(others);
    } else {
        const __m256i bit = _mm256_sllv_epi32(_mm256_set1_epi32(1), lane);
        const __m256i met = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(mask), bit), bit);
        const __m256i bits = _mm256_blendv_epi8(_mm256_set1_epi32(0x7fffffff), _mm256_castps_si256(t), met);
        const __m256i key = _mm256_or_si256(_mm256_andnot_si256(_mm256_set1_epi32(7), bits), lane);
        // rank = how many of the other seven keys are smaller
        __m256i rank = _mm256_setzero_si256(), other = lane;
        for (int i = 1; i < 8; ++i) {
            other = _mm256_and_si256(_mm256_add_epi32(other, _mm256_set1_epi32(1)), _mm256_set1_epi32(7));
            rank = _mm256_sub_epi32(rank, _mm256_cmpgt_epi32(key, _mm256_permutevar8x32_epi32(key, other)));
        }
        alignas(32) std::int32_t ranks[8], order[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(ranks), rank);
        for (int c = 0; c < 8; ++c)
            order[ranks[c]] = c;
        const int n = lane_count8(mask);
        // slot j of the push gets the child of rank n - 1 - j
        const __m256i from = _mm256_and_si256(_mm256_sub_epi32(_mm256_set1_epi32(n - 1), lane), _mm256_set1_epi32(7));
        perm = _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(order)), from);
        enter = order[0];
        pushed = n - 1;
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(stack.child + top), _mm256_permutevar8x32_epi32(children, perm));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(stack.count + top), _mm256_permutevar8x32_epi32(counts, perm));
    _mm256_storeu_ps(stack.t + top, _mm256_permutevar8x32_ps(t, perm));
    top += pushed;
    child = node.child[enter];
    count = node.count[enter];
}
#endif

/// The children met (`mask`, not 0) of `node`, whose entry distances are
/// tnear: sets child and count to the one to enter, pushes the others.
template <bool any_hit, class Stack>
RT_BVH_INLINE void descend(int mask, const bvh_node& node, const real tnear[], Stack& stack, int& top, std::uint32_t& child,
                           std::uint32_t& count)
{
#if RT_BVH_AVX2
#define RT_BVH_ONE(k, a) \
    case k: child = node.child[a]; count = node.count[a]; return;
#define RT_BVH_TWO(k, a, b) \
    case k: descend_pair<a, b, any_hit>(node, tnear, stack, top, child, count); return;
    switch (mask_case.of[mask]) {
    RT_BVH_ONE(0, 0) RT_BVH_ONE(1, 1) RT_BVH_ONE(2, 2) RT_BVH_ONE(3, 3)
    RT_BVH_ONE(4, 4) RT_BVH_ONE(5, 5) RT_BVH_ONE(6, 6) RT_BVH_ONE(7, 7)
    RT_BVH_TWO(8, 0, 1) RT_BVH_TWO(9, 0, 2) RT_BVH_TWO(10, 0, 3) RT_BVH_TWO(11, 0, 4)
    RT_BVH_TWO(12, 0, 5) RT_BVH_TWO(13, 0, 6) RT_BVH_TWO(14, 0, 7) RT_BVH_TWO(15, 1, 2)
    RT_BVH_TWO(16, 1, 3) RT_BVH_TWO(17, 1, 4) RT_BVH_TWO(18, 1, 5) RT_BVH_TWO(19, 1, 6)
    RT_BVH_TWO(20, 1, 7) RT_BVH_TWO(21, 2, 3) RT_BVH_TWO(22, 2, 4) RT_BVH_TWO(23, 2, 5)
    RT_BVH_TWO(24, 2, 6) RT_BVH_TWO(25, 2, 7) RT_BVH_TWO(26, 3, 4) RT_BVH_TWO(27, 3, 5)
    RT_BVH_TWO(28, 3, 6) RT_BVH_TWO(29, 3, 7) RT_BVH_TWO(30, 4, 5) RT_BVH_TWO(31, 4, 6)
    RT_BVH_TWO(32, 4, 7) RT_BVH_TWO(33, 5, 6) RT_BVH_TWO(34, 5, 7) RT_BVH_TWO(35, 6, 7)
    default: descend_many<any_hit>(mask, node, tnear, stack, top, child, count); return;
    }
#undef RT_BVH_ONE
#undef RT_BVH_TWO
#else
    switch (mask) {
    case 1: descend4<1, any_hit>(node, tnear, stack, top, child, count); return;
    case 2: descend4<2, any_hit>(node, tnear, stack, top, child, count); return;
    case 3: descend4<3, any_hit>(node, tnear, stack, top, child, count); return;
    case 4: descend4<4, any_hit>(node, tnear, stack, top, child, count); return;
    case 5: descend4<5, any_hit>(node, tnear, stack, top, child, count); return;
    case 6: descend4<6, any_hit>(node, tnear, stack, top, child, count); return;
    case 7: descend4<7, any_hit>(node, tnear, stack, top, child, count); return;
    case 8: descend4<8, any_hit>(node, tnear, stack, top, child, count); return;
    case 9: descend4<9, any_hit>(node, tnear, stack, top, child, count); return;
    case 10: descend4<10, any_hit>(node, tnear, stack, top, child, count); return;
    case 11: descend4<11, any_hit>(node, tnear, stack, top, child, count); return;
    case 12: descend4<12, any_hit>(node, tnear, stack, top, child, count); return;
    case 13: descend4<13, any_hit>(node, tnear, stack, top, child, count); return;
    case 14: descend4<14, any_hit>(node, tnear, stack, top, child, count); return;
    default: descend4<15, any_hit>(node, tnear, stack, top, child, count); return;
    }
#endif
}

} // namespace RT_BVH_ABI
} // namespace detail
} // namespace rt

#endif // RT_BVH_DESCEND_W8X / _W8 / _W4

#include "simd_end.hpp"
