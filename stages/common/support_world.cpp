// The library's accelerator for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/bvh/accelerator.hpp>

namespace stage {

world::world(const rt::scene& s, const std::string& kind)
    : impl_(std::make_shared<const rt::accelerator>(s, rt::parse_accelerator_kind(kind)))
{
}

world::~world() = default;

bool world::closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& rec) const
{
    return impl_->closest_hit(r, tmin, tmax, rec);
}

bool world::any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const { return impl_->any_hit(r, tmin, tmax); }

std::string world::kind() const { return rt::name_of(impl_->kind()); }

std::size_t world::primitives() const { return impl_->primitive_count(); }

std::size_t world::nodes() const { return impl_->stats().nodes; }

std::string simd_path() { return rt::describe(rt::accelerator::automatic_path()); }

} // namespace stage
