// arguments.hpp - how each parameter of an exercise crosses the link, on both
// sides (tools/grading/judge/README.md).
//
// A parameter is one of three things:
//   - data (it has a wire<T>): sent to the server; when it is a non-const
//     lvalue reference it is an out-parameter and comes back after the call;
//   - a std::ostream& (stage 02's write_ppm): nothing is sent, and what the
//     student wrote to it comes back and is written to the test's stream;
//   - a callback (an accelerator, a hit function, a hit-item callable): only a
//     handle is sent; the server's stand-in calls back through the link, so
//     the test's own object answers, in the judge.
#pragma once

#include <cstdint>
#include <ostream>
#include <type_traits>

#if __has_include(<rt/intersection/hit_list.hpp>)
#include <rt/intersection/hit_list.hpp>
#endif

#include "wire.hpp"

namespace rt {
namespace judge {

template <class T>
using bare = std::remove_cv_t<std::remove_reference_t<T>>;

template <class T, class = void>
struct has_wire : std::false_type {};
template <class T>
struct has_wire<T, std::void_t<decltype(&wire<T>::put)>> : std::true_type {};

template <class P>
constexpr bool is_stream = std::is_same<bare<P>, std::ostream>::value;

/// A parameter whose value comes back: a non-const lvalue reference to data or a stream.
template <class P>
constexpr bool is_out = std::is_lvalue_reference<P>::value && !std::is_const<std::remove_reference_t<P>>::value &&
                        (has_wire<bare<P>>::value || is_stream<P>);

/// A pointer to a value the callee reads (or nullptr): the value crosses, and the
/// callee gets a pointer to its copy.
template <class P, class = void>
struct is_pointer_in : std::false_type {};
template <class P>
struct is_pointer_in<P, std::enable_if_t<std::is_pointer<bare<P>>::value &&
                                         std::is_const<std::remove_pointer_t<bare<P>>>::value &&
                                         has_wire<std::remove_cv_t<std::remove_pointer_t<bare<P>>>>::value>>
    : std::true_type {};

template <class P>
constexpr bool is_callback = !has_wire<bare<P>>::value && !is_stream<P> && !is_pointer_in<P>::value;

/// Types that cross whole every time, even as a const reference (remote.hpp).
template <class T>
struct never_kept : std::false_type {};

/// A parameter the callee only reads (a scene, the groups, a ray): when its bytes are those
/// of the same parameter in the function's last call, only a mark crosses, and the callee
/// uses the copy it kept. A test that traces 6,000 rays through one scene sends it once.
template <class P>
constexpr bool is_kept = std::is_lvalue_reference<P>::value && std::is_const<std::remove_reference_t<P>>::value &&
                         has_wire<bare<P>>::value && !never_kept<bare<P>>::value;

/// Values smaller than this cross whole: comparing them costs more than sending them.
constexpr std::size_t kept_from_bytes = 256;

/// The handle the judge sends for rt::hit_shape itself: the server then calls its own
/// copy instead of calling back for every shape.
constexpr std::uint32_t own_hit_shape = 0xffffffffu;

/// The first call target that is a callback, not an exercise: target = callbacks + handle.
constexpr std::uint32_t callbacks = 0x10000u;

/// What a callback is asked to do: the first byte of its call.
enum class callback_method : std::uint8_t { closest_hit = 0, any_hit = 1, hit_item = 2, hit_shape = 3 };

} // namespace judge
} // namespace rt
