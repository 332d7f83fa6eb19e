// mixed_targets.hpp - what each translation unit of library_mixed_targets
// reports: the same scene and rays traced by the BVH as that unit compiles it.
// tests/library_mixed_targets.cpp is built for the default target;
// tests/mixed_targets_unit.cpp, linked into the same program, with -mavx2
// where this machine runs it (tests/CMakeLists.txt), so the two units see
// different fast paths (4-wide and 8-wide nodes, bvh/layout.hpp).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <typeinfo>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/scene.hpp>

namespace rt_test {

/// One unit's view of the fast path and its answers.
struct unit_trace {
    int width = 0;             ///< rt::bvh_width there
    std::string node_type;     ///< typeid(rt::detail::bvh_node).name() there
    std::string accelerator_type; ///< typeid(rt::accelerator).name() there
    std::vector<float> t;      ///< each ray's closest hit (infinity: none), through rt::accelerator
    std::vector<std::uint32_t> primitive; ///< and the primitive hit
    std::vector<bool> blocked; ///< each ray's any_hit in [0, 1e30]
};

/// The rays through `s`, traced by an accelerator the calling unit builds
/// (kind bvh), as that unit is compiled. Internal linkage on purpose: each
/// unit keeps its own copy, where an inline function would be one definition
/// the linker picks for both.
namespace {
[[maybe_unused]] unit_trace trace_in_this_unit(const rt::scene& s, const std::vector<rt::ray>& rays)
{
    unit_trace out;
    out.width = rt::bvh_width;
    out.node_type = typeid(rt::detail::bvh_node).name();
    out.accelerator_type = typeid(rt::accelerator).name();
    const rt::accelerator accel(s, rt::accelerator_kind::bvh);
    for (const rt::ray& r : rays) {
        rt::hit_record rec;
        const bool hit = accel.closest_hit(r, 0, std::numeric_limits<float>::infinity(), rec);
        out.t.push_back(hit ? float(rec.t) : std::numeric_limits<float>::infinity());
        out.primitive.push_back(hit ? rec.primitive : 0u);
        out.blocked.push_back(accel.any_hit(r, 0, rt::real(1e30)));
    }
    return out;
}
} // namespace

/// trace_in_this_unit as the second unit (mixed_targets_unit.cpp) compiles it.
unit_trace trace_in_second_unit(const rt::scene& s, const std::vector<rt::ray>& rays);

} // namespace rt_test
