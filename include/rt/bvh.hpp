// bvh.hpp - the fast path's entry point: includes the whole of include/rt/bvh/
// (rt::bvh, its builder, its SIMD tests). The map of that folder, one concept
// per header, is at the top of bvh/bvh.hpp.
#pragma once

#include "bvh/bvh.hpp"
