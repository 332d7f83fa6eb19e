// decimal_text.hpp - a decimal number read from text the same way with every
// standard library: the one reader of the numbers of scene, OBJ and MTL files
// (text_line.hpp), of camera_text.hpp's read-back and of the programs'
// options (stages/common/command_line.hpp).
//
//     double value = 0;
//     const rt::detail::decimal_reading reading =
//         rt::detail::read_decimal<rt::real>(text.data(), text.data() + text.size(), value);
//     if (reading == rt::detail::decimal_reading::number)
//         store(rt::real(value));   // the rt::real nearest the text, exactly
//
// What is read: all of [first, last) as one number, "[+|-]digits[.digits]
// [(e|E)[+|-]digits]" (".5" and "5." too), in the C locale's spelling
// whatever the program's locale. Nothing is skipped but one leading '+': no
// blanks, no hexadecimal, no second sign; "inf", "infinity" and "nan" (any
// case, "nan(chars)" too) are read and called not finite. The value is the
// double nearest the text (ties to even), and a number beyond double's range
// is too large while one below its smallest subnormal is a zero of the text's
// sign, as IEEE 754 rounds it.
//
// Why not std::stod or std::strtod: they read the decimal point of the C
// locale (in a German one "0.5" stops at the '.'), skip leading blanks and
// take hexadecimal. Why not std::from_chars alone: libc++ before 20 (macOS's
// Xcode) has deleted its overloads for double. So the parser is fast_float
// (Lemire, "Number Parsing at a Gigabyte per Second", Software: Practice and
// Experience 51(8), 2021) where its header is found, and otherwise
// std::from_chars where the standard library says it has it for double
// (__cpp_lib_to_chars: libstdc++ 11 and later, MSVC 2019 16.4 and later;
// libc++'s <version> leaves the macro undefined, also from 20 on, where the
// overloads exist, so libc++ always takes fast_float). Both are
// correctly rounded (libstdc++ 12 itself parses with fast_float); fast_float
// is preferred where both exist because it reads a number faster, inline
// (the figures: docs/architecture.md, "Figures behind the comments").
// The two differ where the standard leaves room (C++17 [charconv.from.chars],
// LWG 3081): beyond the range std::from_chars reports result_out_of_range and
// leaves the value alone (libstdc++) or writes 0 or inf (MSVC, fast_float 4
// and later); fast_float 3 reports success with inf or 0. read_decimal
// decides each case from the text instead, so every backend reads alike.
//
// rt::real may be float, and the double nearest the text, rounded once more
// to float, can miss the float nearest the text ("double rounding": Boldo &
// Melquiond, "Emulation of FMA and correctly rounded sums: proved algorithms
// using rounding to odd", IEEE Transactions on Computers 57(4), 2008). It
// does only when the double lies exactly halfway between two floats and the
// text does not: every halfway point between floats is a double (it has 25
// significant bits), so rounding to double, which keeps order, leaves the
// text's double on the text's side of each or on the point itself. So
// read_decimal<float> tests for that one case (a few bit operations) and then
// parses the text as a float.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <system_error>
#include <type_traits>

#if __has_include(<fast_float/fast_float.h>)
#include <fast_float/fast_float.h>
#endif

#if !(defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L) && !__has_include(<fast_float/fast_float.h>)
#error "rt reads numbers with std::from_chars for double, which this standard library lacks (libc++ before 20: macOS), or with fast_float: install it (Debian/Ubuntu: sudo apt-get install libfast-float-dev; Homebrew: brew install fast_float; vcpkg: vcpkg install fast-float) and link rt::rt through CMake, or add its include directory"
#endif

namespace rt {
namespace detail {

/// What read_decimal made of a text.
enum class decimal_reading {
    number,       ///< a finite number
    not_a_number, ///< not all of the text is one decimal number
    not_finite,   ///< "inf", "infinity" or "nan", with either sign
    too_large,    ///< a magnitude beyond double's largest
};

/// One backend's parse of a number: where it stopped, and std::errc() or why not.
struct decimal_parse {
    const char* end;
    std::errc status;
};

#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
/// The standard library's parser.
struct from_chars_parser {
    template <class Float>
    static decimal_parse parse(const char* first, const char* last, Float& value) noexcept
    {
        const std::from_chars_result parsed = std::from_chars(first, last, value);
        return {parsed.ptr, parsed.ec};
    }
};
#endif

#if __has_include(<fast_float/fast_float.h>)
/// fast_float's parser.
struct fast_float_parser {
    template <class Float>
    static decimal_parse parse(const char* first, const char* last, Float& value) noexcept
    {
        const fast_float::from_chars_result parsed = fast_float::from_chars(first, last, value);
        return {parsed.ptr, parsed.ec};
    }
};
#endif

/// The parser of the top of this file: fast_float where it is found, the
/// standard library's otherwise.
#if __has_include(<fast_float/fast_float.h>)
using decimal_parser = fast_float_parser;
#else
using decimal_parser = from_chars_parser;
#endif

/// Whether a decimal number a parser found beyond double's range, [first,
/// last) without a leading '+', lies above it (else below the smallest
/// subnormal): the decimal exponent of its first significant digit
/// (d.ddd x 10^magnitude) says which, as parsers tell only "out of range".
inline bool beyond_double(const char* first, const char* last) noexcept
{
    long long digits = 0, zeros = 0, exponent = 0;
    bool point = false, significant = false;
    const char* p = first != last && *first == '-' ? first + 1 : first;
    for (; p != last && ((*p >= '0' && *p <= '9') || *p == '.'); ++p) {
        if (*p == '.') {
            point = true;
        } else if (!point) {
            significant = significant || *p != '0';
            digits += significant ? 1 : 0;
        } else if (!significant) {
            significant = *p != '0';
            zeros += significant ? 0 : 1;
        }
    }
    if (p != last && (*p == 'e' || *p == 'E')) {
        ++p;
        const bool negative = p != last && *p == '-';
        if (p != last && (*p == '+' || *p == '-'))
            ++p;
        // saturated far beyond any count of digits a text can hold
        for (; p != last; ++p)
            exponent = exponent < 1000000000000000LL ? exponent * 10 + (*p - '0') : exponent;
        exponent = negative ? -exponent : exponent;
    }
    return (digits > 0 ? digits - 1 : -(zeros + 1)) + exponent > 0;
}

/// 2^128 - 2^103, halfway between float's largest and 2^128: a magnitude below
/// it rounds to a finite float, one at or above it to infinity (IEEE 754-2019,
/// sec. 4.3.1: at least b^emax (b - b^(1-p) / 2) rounds to infinity).
constexpr double float_rounding_limit = 0x1.ffffffp+127;

/// Whether the double `d`, of magnitude at most float_rounding_limit, lies exactly
/// halfway between two adjacent floats (the double rounding case of the top
/// of this file).
inline bool halfway_between_floats(double d) noexcept
{
    static_assert(std::numeric_limits<double>::is_iec559 && std::numeric_limits<float>::is_iec559,
                  "IEEE 754 binary32 and binary64");
    std::uint64_t bits = 0;
    std::memcpy(&bits, &d, sizeof bits);
    const int biased_exponent = int(bits >> 52 & 0x7ff);
    if (biased_exponent >= 1023 - 126) {
        // float's normal range: a float keeps the first 23 of the double's 52
        // fraction bits; halfway between two, the next bit (bit 28) is 1 and
        // the 28 below it are 0
        return (bits & 0x1fffffffu) == 0x10000000u;
    }
    // below it the floats are the multiples of 2^-149 (subnormal): halfway
    // between two is an odd multiple of 2^-150 (the scaling is exact)
    const double scaled = std::fabs(d) * 0x1p150;
    return std::floor(scaled) == scaled && std::fmod(scaled, 2.0) == 1.0;
}

/// Reads all of [first, last) as one decimal number (see the top of this
/// file) into `value`: the double nearest the text, and when `Real` is float
/// a double whose rounding to float is the float nearest the text. `value`
/// is set only for decimal_reading::number. `Parser`: another backend, for
/// the tests.
template <class Real, class Parser = decimal_parser>
decimal_reading read_decimal(const char* first, const char* last, double& value) noexcept
{
    static_assert(std::is_same_v<Real, float> || std::is_same_v<Real, double>, "Real is float or double");
    if (first != last && *first == '+') {
        ++first;
        if (first != last && (*first == '+' || *first == '-'))
            return decimal_reading::not_a_number;
    }
    double parsed = 0;
    const decimal_parse result = Parser::parse(first, last, parsed);
    if (result.end != last || (result.status != std::errc() && result.status != std::errc::result_out_of_range))
        return decimal_reading::not_a_number;
    const bool negative = *first == '-'; // a parse succeeded: the text is not empty
    if (result.status == std::errc::result_out_of_range) {
        if (beyond_double(first, last))
            return decimal_reading::too_large;
        parsed = negative ? -0.0 : 0.0;
    } else if (!std::isfinite(parsed)) {
        // inf from digits is fast_float 3's overflow (it reports no error)
        const char lead = first[negative ? 1 : 0];
        return (lead >= '0' && lead <= '9') || lead == '.' ? decimal_reading::too_large : decimal_reading::not_finite;
    }
    if constexpr (std::is_same_v<Real, float>) {
        if (std::fabs(parsed) <= float_rounding_limit && halfway_between_floats(parsed)) {
            float nearest = 0;
            const decimal_parse again = Parser::parse(first, last, nearest);
            // out of float's range there are two such points: 2^-150, halfway
            // between 0 and the smallest subnormal (a zero then), and the limit
            // (the text lies at or above it: the double stays, too large)
            if (again.status == std::errc() && std::isfinite(nearest))
                parsed = double(nearest);
            else if (std::fabs(parsed) < 1)
                parsed = negative ? -0.0 : 0.0;
        }
    }
    value = parsed;
    return decimal_reading::number;
}

/// A value read_decimal<Real> gave, as the Real it rounds to (a double equal
/// to that Real) where that is finite; beyond Real's range, the value itself,
/// for the caller's range check. So the text of float's largest,
/// "3.4028235e38", whose double lies above it, is float's largest.
template <class Real>
double rounded_to(double value) noexcept
{
    static_assert(std::is_same_v<Real, float> || std::is_same_v<Real, double>, "Real is float or double");
    if constexpr (std::is_same_v<Real, float>) {
        const double magnitude = std::fabs(value);
        if (magnitude >= float_rounding_limit)
            return value;
        // rounds down to the largest float; spelled out, as C++17
        // [conv.double]/1 leaves a conversion beyond the largest to the implementation
        if (magnitude > double(std::numeric_limits<float>::max()))
            return std::copysign(double(std::numeric_limits<float>::max()), value);
        return double(float(value));
    } else {
        return value;
    }
}

} // namespace detail
} // namespace rt
