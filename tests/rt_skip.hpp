// rt_skip.hpp - RT_SKIP(reason): a case that cannot run here says why and ends.
//
// The case is then counted skipped, never passed: the runner
// (tests/doctest_main.cpp) exits 77, ctest's skip code, when every case it ran
// skipped, and 1 when any check failed, before or after a skip.
#pragma once

#include <string>

namespace rt_test {

/// Marks the running case skipped and prints "SKIPPED: reason" (tests/doctest_main.cpp).
/// Use RT_SKIP, which also ends the case: nothing may be checked after a skip.
void skip_case(const std::string& reason);

} // namespace rt_test

/// Ends the running case as skipped, with its reason in the test's output. A check
/// that failed before the skip still fails the case. In a SUBCASE it ends the whole
/// case (doctest finds the later subcases only by running into them).
#define RT_SKIP(reason)                                                                                                \
    do {                                                                                                               \
        ::rt_test::skip_case(reason);                                                                                  \
        return;                                                                                                        \
    } while (false)
