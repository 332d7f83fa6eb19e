// Stage 08 - output: the color pipeline from a linear radiance to the value
// an 8-bit file stores: exposure, tone map (tonemap.hpp), transfer function
// (transfer.hpp), in that order (encoding.hpp).
//
// Expected values are closed forms worked out by hand in each case (the
// formulas and their sources are in the headers). The last step, rounding to
// one of 256 byte levels, is stage 02's quantize; the cases here stop at the
// value in [0, 1] before it (the given nearest_byte_level stands in where a
// case speaks of bytes), so they test stage 08 alone. The store itself
// (PPM, PNG, PFM, atomic writes) is library code, tested in
// tests/library_image_output.cpp.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include <rt/core/byte_level.hpp>
#include <rt/output/encoding.hpp>
#include <rt/output/tonemap.hpp>
#include <rt/output/transfer.hpp>

// ===========================================================================
// tone maps, exposure, transfer functions

TEST_CASE("clamp tone map: identity on [0, 1], 0 below, 1 above, NaN to 0")
{
    INFO("expected T(x) = x on [0, 1], 1 above (inf too), 0 below and for NaN (write !(x > 0) to catch NaN)");
    CHECK(rt::tonemap_clamp(0.0f) == 0.0f);
    CHECK(rt::tonemap_clamp(0.25f) == 0.25f);
    CHECK(rt::tonemap_clamp(1.0f) == 1.0f);
    CHECK(rt::tonemap_clamp(7.5f) == 1.0f);
    CHECK(rt::tonemap_clamp(-2.0f) == 0.0f);
    CHECK(rt::tonemap_clamp(std::numeric_limits<float>::infinity()) == 1.0f);
    CHECK(rt::tonemap_clamp(std::nanf("")) == 0.0f);
}

TEST_CASE("Reinhard tone map x / (1 + x) at known points")
{
    {
        INFO("expected T(x) = x / (1 + x): T(0) = 0, T(1) = 1/2, T(3) = 3/4, T(1/4) = 1/5, T(99) = 0.99");
        CHECK(rt::tonemap_reinhard(0.0f) == 0.0f);
        CHECK(rt::tonemap_reinhard(1.0f) == doctest::Approx(0.5));  // 1 / 2
        CHECK(rt::tonemap_reinhard(3.0f) == doctest::Approx(0.75)); // 3 / 4
        CHECK(rt::tonemap_reinhard(0.25f) == doctest::Approx(0.2)); // (1/4) / (5/4)
        CHECK(rt::tonemap_reinhard(99.0f) == doctest::Approx(0.99));
    }
    CHECK_MESSAGE(rt::tonemap_reinhard(std::numeric_limits<float>::infinity()) == 1.0f,
                  "expected T(inf) = 1, the limit of x / (1 + x); computed as written, inf / inf is NaN (a black pixel): "
                  "return 1 for an infinite x");
    CHECK_MESSAGE(rt::tonemap_reinhard(-1.0f) == 0.0f, "expected 0 for x <= 0 (no negative light); x / (1 + x) at -1 divides by 0");
    CHECK_MESSAGE(rt::tonemap_reinhard(std::nanf("")) == 0.0f, "expected 0 for a NaN sample (a black pixel, not NaN bytes)");
    // increasing and below 1 everywhere
    float previous = 0;
    for (float x = 0.01f; x < 1000; x *= 1.1f) {
        const float t = rt::tonemap_reinhard(x);
        CAPTURE(x);
        REQUIRE_MESSAGE(t > previous, "expected T increasing: T(x) = " << t << " after " << previous);
        REQUIRE_MESSAGE(t < 1.0f, "expected T(x) < 1 for every finite x, found " << t);
        previous = t;
    }
}

TEST_CASE("the naive x / (1 + x) turns an infinite sample into a black pixel, the tone map does not")
{
    // a single overflowing sample (inf radiance) must come out white, not black
    const float inf = std::numeric_limits<float>::infinity();
    const float naive = inf / (1.0f + inf);
    CHECK_MESSAGE(std::isnan(naive), "expected inf / (1 + inf) = inf / inf to be NaN (IEEE 754)");
    // the 8-bit store (quantize, stage 02) keeps a NaN as 0: a black pixel
    // your functions are called before the checks, never inside a message: a message is
    // worked out while a failure is reported, where an unfinished exercise's exception
    // would end the whole suite instead of this case
    const float mapped = rt::tonemap_reinhard(inf);
    CHECK_MESSAGE(mapped == 1.0f, "expected tonemap_reinhard(inf) to be the limit 1 (white once stored), not "
                                  "inf / inf = NaN (a black pixel once stored); found " << mapped);
    const float encoded = rt::srgb_encode(mapped);
    CHECK_MESSAGE(encoded == doctest::Approx(1.0),
                  "expected an infinite sample encoded as 1, white: sRGB(1) = 1.055 - 0.055 = 1");
}

TEST_CASE("ACES filmic fit: T(1) = 2.54 / 3.16, reaches 1 at x = 7.24 and stays there")
{
    // T(x) = x(2.51 x + 0.03) / (x(2.43 x + 0.59) + 0.14)
    INFO("expected Narkowicz's fit T(x) = x(2.51 x + 0.03) / (x(2.43 x + 0.59) + 0.14), clamped to [0, 1]: T(0) = 0, "
         "T(1) = 2.54 / 3.16, 1 from x = 7.2417 on (inf too), 0 for x < 0 and NaN, increasing below 7.24");
    CHECK(rt::tonemap_aces(0.0f) == 0.0f);
    CHECK(rt::tonemap_aces(1.0f) == doctest::Approx(2.54 / 3.16)); // 0.8038: "1 maps to about 0.8"
    // T(x) = 1 where 0.08 x^2 - 0.56 x - 0.14 = 0: x = (0.56 + sqrt(0.56^2 + 4 * 0.08 * 0.14)) / 0.16
    const double x_one = (0.56 + std::sqrt(0.56 * 0.56 + 4 * 0.08 * 0.14)) / 0.16;
    CHECK(x_one == doctest::Approx(7.2417).epsilon(1e-4));
    // computed before the checks, never inside a message (see the case above)
    const float below_one = rt::tonemap_aces(float(x_one) * 0.98f);
    CHECK_MESSAGE(below_one < 1.0f, "expected T(x) below 1 at x = 0.98 * 7.2417 = " << float(x_one) * 0.98f
                                                                                 << ", found " << below_one);
    const float past_one = rt::tonemap_aces(float(x_one) * 1.02f);
    CHECK_MESSAGE(past_one == 1.0f, "expected T(x) = 1 at x = 1.02 * 7.2417 = "
                                        << float(x_one) * 1.02f
                                        << " (beyond 7.2417 the fit is above 1, on its way to 2.51 / 2.43 = 1.033: "
                                           "clamp it to 1), found "
                                        << past_one);
    const float huge = rt::tonemap_aces(1e30f);
    CHECK_MESSAGE(huge == 1.0f, "expected T(1e30) = 1: there x (2.51 x + 0.03) overflows float to inf, and inf / inf "
                                "is NaN; found " << huge);
    CHECK(rt::tonemap_aces(std::numeric_limits<float>::infinity()) == 1.0f);
    CHECK(rt::tonemap_aces(-3.0f) == 0.0f);
    CHECK(rt::tonemap_aces(std::nanf("")) == 0.0f);
    float previous = 0;
    for (float x = 0.01f; x < 7.0f; x += 0.01f) {
        const float t = rt::tonemap_aces(x);
        CAPTURE(x);
        REQUIRE_MESSAGE(t > previous, "expected T increasing below x = 7.24: T(x) = " << t << " after " << previous
                                                                                    << " at x - 0.01");
        previous = t;
    }
}

TEST_CASE("sRGB encode at known points (IEC 61966-2-1)")
{
    // a plain power curve, named: x^(1/2.2) at 1/2 is 0.72974, sRGB's 0.735357
    const double half = double(rt::srgb_encode(0.5f));
    const bool plain_gamma = std::fabs(half - std::pow(0.5, 1 / 2.2)) < 1e-5;
    INFO("expected V = 12.92 x for x <= 0.0031308, else 1.055 x^(1/2.4) - 0.055 (IEC 61966-2-1), increasing, with "
         "srgb_decode its inverse"
         << std::string(plain_gamma ? "; found x^(1/2.2) at x = 1/2: a plain gamma 2.2, not the sRGB curve (a line "
                                      "near 0, then the offset power 1.055 x^(1/2.4) - 0.055)"
                                    : ""));
    CHECK(rt::srgb_encode(0.0f) == 0.0f);
    CHECK(rt::srgb_encode(1.0f) == doctest::Approx(1.0).epsilon(1e-6)); // 1.055 - 0.055
    // 1.055 * 0.5^(1/2.4) - 0.055
    CHECK(rt::srgb_encode(0.5f) == doctest::Approx(1.055 * std::pow(0.5, 1 / 2.4) - 0.055).epsilon(1e-6));
    CHECK(rt::srgb_encode(0.5f) == doctest::Approx(0.7353570).epsilon(1e-6));
    // the linear segment: slope 12.92 below the threshold
    CHECK(rt::srgb_encode(0.001f) == doctest::Approx(0.01292).epsilon(1e-6));
    CHECK(rt::srgb_encode(0.002f) == doctest::Approx(0.02584).epsilon(1e-6));
    // the two pieces meet at 0.0031308: 12.92 x = 0.04044994 and the power piece 0.04044991
    const float x0 = 0.0031308f;
    const float below = rt::srgb_encode(std::nextafter(x0, 0.0f));
    const float above = rt::srgb_encode(std::nextafter(x0, 1.0f));
    CHECK(below == doctest::Approx(0.0404499).epsilon(1e-5));
    CHECK_MESSAGE(std::fabs(above - below) < 1e-6f, "expected the two pieces to meet at x = 0.0031308: just below it "
                                                    "the encoding is "
                                                        << below << ", just above it " << above);
    // increasing, and decode inverts it
    float previous = -1;
    for (int k = 0; k <= 1000; ++k) {
        const float x = float(k) / 1000;
        const float v = rt::srgb_encode(x);
        CAPTURE(x);
        REQUIRE_MESSAGE(v > previous, "expected the encoding increasing: srgb_encode(x) = " << v << " after "
                                                                                           << previous << " at x - 0.001");
        REQUIRE_MESSAGE(rt::srgb_decode(v) == doctest::Approx(x).epsilon(1e-5).scale(1e-3),
                        "expected srgb_decode(srgb_encode(x)) = x: srgb_encode(x) = "
                            << v << ", which the given srgb_decode turns back into " << rt::srgb_decode(v)
                            << "; the linear piece ends at x = 0.0031308 (0.04045 is where the decode's ends, "
                               "at V = 12.92 * 0.0031308)");
        previous = v;
    }
    // the decode side's own known point: v = 0.04045 is x = 0.04045 / 12.92
    CHECK(rt::srgb_decode(0.04045f) == doctest::Approx(0.04045 / 12.92).epsilon(1e-6));
}

TEST_CASE("a plain gamma 2.2 is not sRGB: up to 9 byte levels apart in the shadows")
{
    // both encodings of an x in [0, 1] are in [0, 1], so the given nearest_byte_level
    // (byte_level.hpp) stores them as quantize would
    // by hand: x = 0.001 gives sRGB 12.92 x = 0.01292 -> byte 3, but
    // 0.001^(1/2.2) = 0.0433 -> byte 11; at mid-grey 0.18 the two are 118 and 117
    INFO("by hand: x = 0.001 is byte 3 in sRGB (12.92 x = 0.01292) and 11 with gamma 2.2 (x^(1/2.2) = 0.0433); "
         "x = 0.18 is 118 and 117");
    CHECK(int(rt::nearest_byte_level(rt::srgb_encode(0.001f))) == 3);
    CHECK(int(rt::nearest_byte_level(rt::gamma_encode(0.001f, 2.2f))) == 11);
    CHECK(int(rt::nearest_byte_level(rt::srgb_encode(0.18f))) == 118);
    CHECK(int(rt::nearest_byte_level(rt::gamma_encode(0.18f, 2.2f))) == 117);
    int worst = 0;
    float worst_x = 0;
    int worst_above_tenth = 0;
    for (int k = 0; k <= 100000; ++k) {
        const float x = float(k) / 100000;
        const int d = std::abs(int(rt::nearest_byte_level(rt::gamma_encode(x, 2.2f))) - int(rt::nearest_byte_level(rt::srgb_encode(x))));
        if (d > worst) {
            worst = d;
            worst_x = x;
        }
        if (x >= 0.1f)
            worst_above_tenth = std::max(worst_above_tenth, d);
    }
    CAPTURE(worst_x);
    INFO("expected the two encodings at most 9 byte levels apart, that worst near x = 0.0013 (sRGB's linear "
         "segment), and at most 2 apart above x = 0.1; found " << worst << " and " << worst_above_tenth);
    CHECK(worst == 9);           // near x = 0.0013, where sRGB is still on its linear segment
    CHECK(worst_x < 0.003f);
    CHECK(worst_above_tenth <= 2);
}

TEST_CASE("the pipeline runs exposure, tone map, transfer in that order, to a value in [0, 1]")
{
    rt::encoding enc;
    enc.exposure = 1;
    enc.tonemap = rt::tonemap_kind::reinhard;
    enc.transfer = rt::transfer_kind::srgb;
    // 0.5 * 2^1 = 1 -> Reinhard 1/2 -> sRGB 0.7353570 (stored as byte round(187.52) = 188)
    INFO("expected exposure first (x 2^exposure), then the tone map, then the transfer curve: "
         "0.5 at exposure 1 is 1, Reinhard 1/2, sRGB 0.7353570; 0 stays 0; 1e9 is 1 (white)");
    CHECK(rt::encode_channel(0.5f, enc) == doctest::Approx(0.7353570).epsilon(1e-6));
    CHECK(rt::encode_channel(0.0f, enc) == doctest::Approx(0.0));
    CHECK(rt::encode_channel(1e9f, enc) == doctest::Approx(1.0).epsilon(1e-6));
    // clamp + gamma 2: 0.125 * 2^1 = 0.25 -> sqrt = 0.5 (byte 128)
    rt::encoding plain;
    plain.exposure = 1;
    plain.transfer = rt::transfer_kind::gamma;
    plain.gamma = 2;
    CHECK(rt::encode_channel(0.125f, plain) == doctest::Approx(0.5).epsilon(1e-6));
    // ACES with exposure -1: 2 * 2^-1 = 1 -> 2.54/3.16 = 0.80380 -> sRGB: 1.055 * 0.80380^(1/2.4) - 0.055
    rt::encoding filmic;
    filmic.exposure = -1;
    filmic.tonemap = rt::tonemap_kind::aces;
    CHECK(rt::encode_channel(2.0f, filmic) == doctest::Approx(1.055 * std::pow(2.54 / 3.16, 1 / 2.4) - 0.055).epsilon(1e-5));
}
