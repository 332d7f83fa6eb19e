// library_mixed_targets.cpp - one program whose translation units are
// compiled for different targets: this one for the default (4-wide nodes in
// SSE on x86-64), tests/mixed_targets_unit.cpp with -mavx2 (8-wide nodes),
// as a program that includes rt's headers may mix them. The fast path's
// width-dependent types and functions live in an inline namespace named after
// the width (bvh/abi_begin.hpp, RT_BVH_ABI), so each unit gets its own: one
// name for two layouts would break the one-definition rule, and the linker,
// keeping one copy of each inline function, could pair one unit's build with
// the other's traversal. No exercise is called.
#include "rt_doctest.hpp"
#include "mixed_targets.hpp"
#include "test_scenes.hpp"

#include <limits>
#include <random>
#include <type_traits>
#include <vector>

TEST_CASE("units compiled for different targets each get their own BVH types, and the same hits")
{
#if !defined(RT_TEST_MIXED_AVX2)
    RT_SKIP("this compiler or machine does not build and run AVX2 code, so both units have one target");
#else
    if (!std::is_same<rt::real, float>::value) {
        RT_SKIP("with rt::real = double both units take the scalar path (4-wide nodes), whatever the target");
    }
    std::mt19937 random(23);
    const rt::scene s = rt_test::random_scene(random, 300, 3000, true);
    const std::vector<rt::ray> rays = rt_test::random_rays(random, 4000);
    const rt_test::unit_trace here = rt_test::trace_in_this_unit(s, rays);
    const rt_test::unit_trace there = rt_test::trace_in_second_unit(s, rays);
    INFO("this unit: width " << here.width << ", node type " << here.node_type << "; the -mavx2 unit: width "
                             << there.width << ", node type " << there.node_type);
    CHECK_MESSAGE(here.width != there.width, "expected the two units to have different node widths (4 and 8)");
    CHECK_MESSAGE(here.node_type != there.node_type,
                  "expected two node layouts to be two types (an inline namespace per width), found one name");
    CHECK_MESSAGE(here.accelerator_type != there.accelerator_type,
                  "expected rt::accelerator, which holds the tree, to be a type of its own in each unit");
    // the answers: equal ray by ray (the BVH's hits do not depend on its width)
    std::size_t differ = 0, hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += here.t[i] < std::numeric_limits<float>::infinity() ? 1 : 0;
        if (here.t[i] != there.t[i] || here.primitive[i] != there.primitive[i] || here.blocked[i] != there.blocked[i])
            ++differ;
    }
    INFO(hits << " of " << rays.size() << " rays hit");
    CHECK(hits > rays.size() / 10);
    CHECK_MESSAGE(differ == 0, "expected both units to find the same hits, found " << differ << " rays that differ");
#endif
}
