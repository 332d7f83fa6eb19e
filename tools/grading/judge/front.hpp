// front.hpp - included before anything else (-include) in every unit of a
// judge and of a student's server (tools/grading/judge/README.md): it
// declares call<ID>(), which the exercise bodies of the other program's
// stages are, then defines it (remote.hpp), after rt's headers that use it.
#pragma once

namespace rt {
namespace judge {

template <unsigned ID, class R, class... P, class... A>
R call(R (*function)(P...), A&&... arguments);

/// The stage whose tests the server answers (its first argument): a server built for
/// several stages picks each region's body by it (tools/grading/judge.py, group_overlay).
/// Defined by server.cpp; the judge never calls it.
int serving_stage();

} // namespace judge
} // namespace rt

#include "remote.hpp"
