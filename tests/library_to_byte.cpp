// library_to_byte.cpp - rt::to_byte (include/rt/image_io.hpp), the early stages'
// conversion of a colour channel to a byte: 0 and 1 exact, NaN and negatives 0.
// No exercise is called.
#include "rt_doctest.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include <rt/camera.hpp>
#include <rt/image_io.hpp>
#include <rt/ray_image.hpp>


TEST_CASE("to_byte: 0 and 1 are exact, NaN and negatives become 0")
{
    CHECK(rt::to_byte(0.0f) == 0);
    CHECK(rt::to_byte(1.0f) == 255);
    CHECK(rt::to_byte(-3.0f) == 0);
    CHECK(rt::to_byte(std::nanf("")) == 0);
    CHECK(rt::to_byte(0.5f, 1.0f) == 128);
}
