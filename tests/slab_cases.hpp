// slab_cases.hpp - the rays on which the textbook slab test fails and the
// robust one holds (rt::hit_box_robust, include/rt/intersection/slab.hpp), counted the same
// way by the library suite (library_slab.cpp) and by the page's figures
// (docs_figures.cpp, docs/stages/04-going-further.md).
//
// The textbook method is the stage-04 exercise itself, rt::hit_box_textbook
// (include/rt/intersection/slab.hpp), whose reference body is the book's form (Fundamentals
// of Computer Graphics, 4th ed., sec. 12.3.1): no copy of the answer sits
// outside its exercise region. Its failures are asserted in the reference
// only; in a student kit the textbook's side says SKIPPED, with the reason
// (tests/textbook_methods.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <rt/core/aabb.hpp>
#include <rt/core/ray.hpp>
#include <rt/intersection/slab.hpp>
#include <rt/core/vec.hpp>

#include "textbook_methods.hpp"

namespace rt_test {

/// The unit box [0, 1]^3 both families are aimed at.
inline rt::aabb unit_box()
{
    rt::aabb box;
    box.lo = rt::vec3(0);
    box.hi = rt::vec3(1);
    return box;
}

/// Rays lying in a face plane of the unit box and crossing that face: for
/// each of the 6 faces (axis k at 0 or 1), origins on the face's plane outside
/// the box at 3 x 3 places (-1, 0.5 and 2 on each of the other two axes, the
/// centre left out: 8 origins), aimed at the 4 points (1/4 or 3/4, 1/4 or 3/4)
/// of the face, with the component along k +0 or -0: 6 x 8 x 4 x 2 = 384 rays,
/// every one of which meets the closed box (inside the face).
inline std::vector<rt::ray> face_plane_rays()
{
    std::vector<rt::ray> rays;
    const rt::real places[3] = {-1, rt::real(0.5), 2};
    const rt::real targets[2] = {rt::real(0.25), rt::real(0.75)};
    for (int k = 0; k < 3; ++k) {
        const int u = (k + 1) % 3, v = (k + 2) % 3;
        for (const rt::real plane : {rt::real(0), rt::real(1)})
            for (const rt::real pu : places)
                for (const rt::real pv : places) {
                    if (pu == rt::real(0.5) && pv == rt::real(0.5))
                        continue; // that origin would lie inside the face
                    for (const rt::real tu : targets)
                        for (const rt::real tv : targets)
                            for (const rt::real zero : {rt::real(0), -rt::real(0)}) {
                                rt::ray r;
                                r.origin[k] = plane;
                                r.origin[u] = pu;
                                r.origin[v] = pv;
                                r.direction[k] = zero;
                                r.direction[u] = tu - pu;
                                r.direction[v] = tv - pv;
                                rays.push_back(r);
                            }
                }
    }
    return rays;
}

/// Rays through the edge x = 1, y = 0 of the unit box at z = 1/2: directions
/// (a, b, c) with integers a, b in 1 .. 31 and c in -3 .. 3, origins
/// (1, 0, 1/2) - s d for s in 1 .. 5 (exact in float and double). In exact
/// arithmetic each leaves the x slab where it enters the y slab: t_near =
/// t_far = s, and the ray touches the closed box. Only the rounded 1/d is
/// inexact, and it can make t_near > t_far: 31 x 31 x 7 x 5 = 33635 rays.
inline std::vector<rt::ray> edge_rays()
{
    std::vector<rt::ray> rays;
    for (int a = 1; a <= 31; ++a)
        for (int b = 1; b <= 31; ++b)
            for (int c = -3; c <= 3; ++c)
                for (int s = 1; s <= 5; ++s) {
                    const rt::vec3 d{rt::real(a), rt::real(b), rt::real(c)};
                    rays.push_back(rt::ray{rt::vec3(1, 0, rt::real(0.5)) - rt::real(s) * d, d});
                }
    return rays;
}

/// How many of `rays` the method says miss the unit box in [0, inf).
template <class Method>
std::size_t misses(const std::vector<rt::ray>& rays, Method method)
{
    const rt::aabb box = unit_box();
    std::size_t count = 0;
    for (const rt::ray& r : rays)
        count += method(box, r) ? 0 : 1;
    return count;
}

/// The book's slab test, stage 04's hit_box_textbook, in [0, inf). Word for
/// word: a = 1/d_k, the near plane by the sign of a, then the book's
/// max(t_xmin, t_ymin, t_zmin) and min(t_xmax, t_ymax, t_zmax), written
/// std::max(std::max(x, y), z): std::max(a, b) is (a < b) ? b : a, so a NaN in
/// x (a ray lying in a plane x = lo or x = hi: 0 * inf) comes first, every
/// comparison with it is false and it survives into the result, which then
/// fails t_enter <= t_exit. A NaN in y or z is dropped by the same rule.
inline bool textbook_hits(const rt::aabb& box, const rt::ray& r)
{
    rt::real tnear = 0;
    return rt::hit_box_textbook(box, r, 0, std::numeric_limits<rt::real>::infinity(), tnear);
}

/// "" when stage 04's hit_box_textbook runs, else its not-done message (a kit
/// where it is not written yet).
inline const std::string& textbook_slab_not_done()
{
    static const std::string why = not_done_message([] { textbook_hits(unit_box(), rt::ray{rt::vec3(-1), rt::vec3(1)}); });
    return why;
}

/// For docs_figures: throws unless textbook_hits is the reference's
/// (require_reference_textbook): the figure is then skipped.
inline void require_textbook_slab()
{
    require_reference_textbook(textbook_slab_not_done(), "hit_box_textbook (stage 04)");
}

inline bool robust_hits(const rt::aabb& box, const rt::ray& r)
{
    rt::real tnear = 0;
    return rt::hit_box_robust(box, r, 0, std::numeric_limits<rt::real>::infinity(), tnear);
}

} // namespace rt_test
