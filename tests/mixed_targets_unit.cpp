// mixed_targets_unit.cpp - the second translation unit of
// library_mixed_targets (see mixed_targets.hpp): built with -mavx2 where this
// machine runs it, so its fast path has 8-wide nodes.
#include "mixed_targets.hpp"

namespace rt_test {

unit_trace trace_in_second_unit(const rt::scene& s, const std::vector<rt::ray>& rays)
{
    return trace_in_this_unit(s, rays);
}

} // namespace rt_test
