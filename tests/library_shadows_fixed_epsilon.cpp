// library_shadows_fixed_epsilon.cpp - the textbook's fixed epsilon
// (rt::light_visible_fixed_epsilon, include/rt/shading/shadows_fixed_epsilon.hpp) fails
// where stage 06's robust offset holds: over the scales and offsets of the
// stage-06 acne table (tests/shadow_acne.hpp), it shows acne. A property of
// the library's comparison method, so it lives here and no student's code is
// judged by it. No exercise is called.
#include "rt_doctest.hpp"
#include "shadow_acne.hpp"

#include <string>

TEST_CASE("the textbook's fixed epsilon (1e-4) shows shadow acne where the robust offset shows none")
{
    int total = 0, worst = 0;
    double worst_scale = 0, worst_offset = 0;
    for (const rt_test::acne_setting& set : rt_test::acne_settings()) {
        const rt_test::shadow_scene q = set.scene();
        const rt_test::shadow_count f = rt_test::count_shadow_errors(q, rt_test::fixed_epsilon_visible);
        total += f.acne;
        if (f.acne > worst) {
            worst = f.acne;
            worst_scale = set.scale();
            worst_offset = set.offset();
        }
    }
    INFO("acne points of the fixed epsilon over every setting: " << total << ", at most " << worst << " (scale "
                                                                 << worst_scale << ", offset " << worst_offset << ")");
    CHECK_MESSAGE(total > 0, "expected the fixed epsilon 1e-4 to show acne at some scale of the stage-06 table");
}
