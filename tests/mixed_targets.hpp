// mixed_targets.hpp - what each translation unit of library_mixed_targets
// reports: the same scene and rays traced by the BVH as that unit compiles it.
// tests/library_mixed_targets.cpp is built for the default target;
// tests/mixed_targets_unit.cpp, linked into the same program, with -mavx2
// where this machine runs it (tests/CMakeLists.txt), so the two units see
// different fast paths (4-wide and 8-wide nodes, bvh/layout.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <rt/ray.hpp>
#include <rt/scene.hpp>

namespace rt_test {

/// One unit's view of the fast path and its answers.
struct unit_trace {
    int width = 0;             ///< rt::bvh_width there
    std::string node_type;     ///< typeid(rt::bvh_node).name() there
    std::string accelerator_type; ///< typeid(rt::accelerator).name() there
    std::vector<float> t;      ///< each ray's closest hit (infinity: none), through rt::accelerator
    std::vector<std::uint32_t> primitive; ///< and the primitive hit
    std::vector<bool> blocked; ///< each ray's any_hit in [0, 1e30]
};

/// The rays through `s`, traced by an accelerator this unit builds (kind bvh).
unit_trace trace_in_second_unit(const rt::scene& s, const std::vector<rt::ray>& rays);

} // namespace rt_test
