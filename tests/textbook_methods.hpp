// textbook_methods.hpp - how the library suites treat the textbook methods
// they compare with the library's robust ones (tests/sphere_accuracy.hpp,
// tests/slab_cases.hpp, tests/library_watertight.cpp). They measure the
// exercises themselves (stage 03's hit_sphere_textbook, stage 04's
// hit_box_textbook and hit_triangle_moller_trumbore), never a copy of them, so
// the only place a student kit holds an answer is its exercise region.
//
//  - In the reference the exercises' bodies are the textbook's, and the suites
//    assert where the textbook fails: RT_REFERENCE_EXERCISES, which
//    tests/CMakeLists.txt defines where tools/make_kit.py sits beside the tests
//    (never in a kit, nor in the copy a submission is graded in).
//  - In a kit, an exercise not written yet throws rt::exercise_not_done: the
//    case of the textbook side skips, with why, and the robust method's cases
//    still run.
//  - Once the student has written it, its figures are printed beside the
//    robust method's and nothing about them is asserted: a method more careful
//    than the book's is never marked down.
#pragma once

#include <stdexcept>
#include <string>

#include <rt/core/error.hpp>

namespace rt_test {

/// True where the exercises' bodies are the reference's (see the top of this file).
#ifdef RT_REFERENCE_EXERCISES
inline constexpr bool exercises_are_the_reference = true;
#else
inline constexpr bool exercises_are_the_reference = false;
#endif

/// Thrown by a figure of a textbook method where the exercise is the student's
/// (tests/docs_figures.cpp skips the figure: the pages quote the reference's).
struct not_the_reference : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Throws, for docs_figures, unless the figures of the textbook method `exercise`
/// are the reference's: its not-done message `not_done` (a kit where it is not
/// written yet), or not_the_reference (a kit where it is the student's).
inline void require_reference_textbook(const std::string& not_done, const std::string& exercise)
{
    if (!not_done.empty())
        throw rt::exercise_not_done(not_done);
    if (!exercises_are_the_reference)
        throw not_the_reference(exercise + " is yours here; the pages quote the reference's");
}

/// "" when `call` (which calls an exercise) returns, else the not-done message
/// the exercise throws (a kit where it is not written yet).
template <class Call>
std::string not_done_message(Call call)
{
    try {
        call();
        return "";
    } catch (const rt::exercise_not_done& e) {
        return e.what();
    }
}

/// Why a case cannot assert what the textbook method `exercise` does, or "" where
/// it can: only in the reference. Elsewhere the case skips with this reason
/// (RT_SKIP): `not_done`, the exercise's not-done message (a kit where it is not
/// written yet), or, when that is "", that the method is the student's own.
inline std::string textbook_skip_reason(const std::string& not_done, const std::string& exercise)
{
    if (!not_done.empty())
        return "the comparison with the textbook needs " + exercise + ", which is not written yet: " + not_done;
    if (!exercises_are_the_reference)
        return "the textbook side is your own " + exercise +
               ": what it does is printed, never asserted (a method more careful than the book's is not marked down)";
    return "";
}

} // namespace rt_test
