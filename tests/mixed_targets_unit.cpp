// mixed_targets_unit.cpp - the second translation unit of
// library_mixed_targets (see mixed_targets.hpp): built with -mavx2 where this
// machine runs it, so its fast path has 8-wide nodes.
#include "mixed_targets.hpp"

#include <limits>
#include <typeinfo>

#include <rt/accelerator.hpp>

namespace rt_test {

unit_trace trace_in_second_unit(const rt::scene& s, const std::vector<rt::ray>& rays)
{
    unit_trace out;
    out.width = rt::bvh_width;
    out.node_type = typeid(rt::bvh_node).name();
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

} // namespace rt_test
