// library_offset.cpp - the robust ray origin of Wachter and Binder (Ray Tracing
// Gems ch. 6, include/rt/intersection/offset.hpp) that stages 06 and 07 use: it lies on the
// normal's side of the surface and moves the point a few ulps only.
#include "rt_doctest.hpp"

#include <cmath>
#include <limits>

#include <rt/intersection/offset.hpp>
#include <rt/core/vec.hpp>

TEST_CASE("the robust origin lies on the normal's side of the surface, and moves a few ulps only")
{
    const rt::vec3 n = glm::normalize(rt::vec3(0.3f, 1.0f, 0.2f));
    for (double magnitude : {1e-6, 1e-2, 1.0, 1e3, 1e6}) {
        const rt::vec3 p = rt::real(magnitude) * rt::vec3(0.6f, -0.48f, 0.64f);
        const rt::vec3 moved = rt::offset_ray_origin(p, n);
        CAPTURE(magnitude);
        CHECK(glm::dot(moved - p, n) > 0);
        // at most 256 ulps of the coordinate in each axis (or 2^-16 near zero)
        for (int axis = 0; axis < 3; ++axis) {
            const rt::real x = std::fabs(p[axis]);
            const double ulp = double(std::nextafter(x, std::numeric_limits<rt::real>::infinity()) - x);
            const double near_zero = sizeof(rt::real) == 4 ? 1.0 / 65536 : 1.0 / 65536 / 536870912.0;
            const double bound = x < rt::real(1.0 / 32) ? near_zero : 256 * ulp;
            CHECK(std::fabs(double(moved[axis] - p[axis])) <= bound * 1.0001);
        }
    }
}
