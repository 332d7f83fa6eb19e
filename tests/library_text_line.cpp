// library_text_line.cpp - the one tokenizer of scene, OBJ and MTL files
// (include/rt/input/text_line.hpp, text_file.hpp): numbers read alike by every
// reader and every parser (decimal_text.hpp), correctly rounded to rt::real
// and whatever the locale, columns across continued lines, scene tokens with
// quotes and comments. No exercise is called.
#include "rt_doctest.hpp"

#include <charconv>
#include <clocale>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <locale>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

#include <rt/core/decimal_text.hpp>
#include <rt/input/obj_line.hpp>
#include <rt/input/scene_statement.hpp>
#include <rt/input/text_file.hpp>
#include <rt/input/text_line.hpp>

namespace {

using reading = rt::detail::number_reading;

std::string reading_name(reading r)
{
    switch (r) {
    case reading::fits: return "fits";
    case reading::not_a_number: return "not a number";
    case reading::not_finite: return "not finite";
    case reading::too_large: return "too large";
    }
    return "?";
}

std::string classify(const std::string& word, double largest, double* value = nullptr)
{
    double v = -1;
    const reading r = rt::detail::read_number(word.data(), word.data() + word.size(), largest, v);
    if (value)
        *value = v;
    return reading_name(r);
}

/// What a reader does with one word: its value, or its error message.
template <class Read>
std::string outcome(Read&& read)
{
    try {
        return "value " + std::to_string(double(read()));
    } catch (const rt::error& e) {
        return e.what();
    }
}

using rt::detail::decimal_reading;

/// What read_decimal<Real, Parser> makes of a text.
struct decimal_result {
    decimal_reading reading = decimal_reading::not_a_number;
    double value = 0;
};

template <class Real, class Parser>
decimal_result read_decimal_with(const std::string& text)
{
    decimal_result result;
    result.value = -7; // no case expects it: a value left unset shows
    result.reading = rt::detail::read_decimal<Real, Parser>(text.data(), text.data() + text.size(), result.value);
    return result;
}

/// Calls check(parser, name) for every parser decimal_text.hpp finds here
/// (the conditions of its top), so that each one is held to the same contract
/// whichever the library takes.
template <class Check>
int for_each_parser(Check&& check)
{
    int parsers = 0;
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
    check(rt::detail::from_chars_parser{}, "std::from_chars");
    ++parsers;
#endif
#if __has_include(<fast_float/fast_float.h>)
    check(rt::detail::fast_float_parser{}, "fast_float");
    ++parsers;
#endif
    return parsers;
}

/// The C library's correctly rounded parsers, written apart from rt's, in the
/// C locale the tests run in (the locale case restores it).
double c_strtod(const std::string& text)
{
    return std::strtod(text.c_str(), nullptr);
}

float c_strtof(const std::string& text)
{
    return std::strtof(text.c_str(), nullptr);
}

/// The rt::real nearest a text, by the C library.
rt::real c_nearest_real(const std::string& text)
{
    if constexpr (std::is_same_v<rt::real, float>)
        return c_strtof(text);
    else
        return c_strtod(text);
}

/// Equal, and of the same sign when zero.
bool same(double a, double b)
{
    return a == b && std::signbit(a) == std::signbit(b);
}

/// What text_line::number makes of one word: the value, or the message.
struct number_outcome {
    bool read = false;
    rt::real value = 0;
    std::string message;
};

number_outcome line_number(const std::string& word)
{
    const std::string text = "v " + word;
    const std::string file = "m.obj";
    const std::vector<rt::line_piece> pieces = {{0, 1, 1}};
    rt::text_line line(file, pieces, text.data(), text.data() + text.size());
    line.word();
    number_outcome result;
    try {
        result.value = line.number("the vertex x");
        result.read = true;
    } catch (const rt::error& e) {
        result.message = e.what();
    }
    return result;
}

/// A decimal comma for the C++ global locale where no installed locale has one.
struct decimal_comma : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
};

} // namespace

TEST_CASE("read_number: a number, NaN and inf, too large for the limit or for double, too small for double")
{
    const double big = std::numeric_limits<double>::max();
    double value = 0;
    CHECK(classify("1.5", big, &value) == "fits");
    CHECK(value == 1.5);
    CHECK(classify("+2", big, &value) == "fits");
    CHECK(value == 2);
    CHECK(classify("-0.25e1", big, &value) == "fits");
    CHECK(value == -2.5);
    CHECK(classify("nan", big) == "not finite");
    CHECK(classify("inf", big) == "not finite");
    CHECK(classify("", big) == "not a number");
    CHECK(classify("-", big) == "not a number");
    CHECK(classify("1.5x", big) == "not a number");
    CHECK(classify("1e39", 3.4e38) == "too large");
    CHECK(classify("1e38", 3.4e38) == "fits");
    // beyond double both ways: a parser says only "out of range" (or gives
    // inf or 0), the decimal exponent of the first significant digit tells which
    CHECK(classify("1e400", big) == "too large");
    CHECK(classify("1000e306", big) == "too large"); // 1e309
    CHECK(classify("-1e400", big) == "too large");
    CHECK(classify("0.001e311", big, &value) == "fits"); // 1e308: a double
    CHECK(value == doctest::Approx(1e308));
    CHECK(classify("1e-400", big, &value) == "fits");
    CHECK(value == 0);
    CHECK(classify("0.0001e-321", big, &value) == "fits"); // 1e-325: below the smallest subnormal
    CHECK(value == 0);
    CHECK(classify("123e-330", big, &value) == "fits");
    CHECK(value == 0);
}

TEST_CASE("read_decimal: the hard inputs, read alike by every parser")
{
    const int parsers = for_each_parser([](auto parser, const char* name) {
        using Parser = decltype(parser);
        INFO("parser " << std::string(name));
        const auto as_double = [](const std::string& text) { return read_decimal_with<double, Parser>(text); };
        const auto as_float = [](const std::string& text) { return read_decimal_with<float, Parser>(text); };

        // numbers: the double and the float nearest the text, as the C
        // library's strtod and strtof give them
        for (const char* text : {"0.1", "3.4028235e38", "3.4028236e38", "3.40282356e38", "1e-45", "1.4e-45",
                                 "4.9e-324", "2.2250738585072011e-308", "1e-50", "0.30000000000000004",
                                 "1.7976931348623157e308", "-0", "+1.5", ".5", "5.", "1e-400", "-1e-400",
                                 "-2.5E-3", "007", "1.000000059604644775390626"}) {
            INFO("the text '" << std::string(text) << "'");
            const decimal_result d = as_double(text);
            CHECK(d.reading == decimal_reading::number);
            CHECK(same(d.value, c_strtod(text)));
            const decimal_result f = as_float(text);
            CHECK(f.reading == decimal_reading::number);
            if (std::fabs(f.value) <= double(std::numeric_limits<float>::max())) // else the caller's range check
                CHECK(same(float(f.value), c_strtof(text)));
        }
        // the same values, stated
        CHECK(as_double("0.1").value == 0x1.999999999999ap-4);
        CHECK(float(as_float("0.1").value) == 0x1.99999ap-4f);
        CHECK(float(as_float("3.4028235e38").value) == std::numeric_limits<float>::max());
        // at or beyond 2^128 - 2^103, halfway between the largest float and
        // 2^128, the nearest float is infinite: the double stays for the
        // caller's range check (rounded_to)
        CHECK(std::isinf(c_strtof("3.4028236e38")));
        CHECK(as_float("3.4028236e38").value == c_strtod("3.4028236e38"));
        // subnormals: 2^-149 (1.401e-45) is float's smallest, 2^-1074 (4.94e-324) double's
        CHECK(float(as_float("1e-45").value) == std::numeric_limits<float>::denorm_min());
        CHECK(float(as_float("1.4e-45").value) == std::numeric_limits<float>::denorm_min());
        CHECK(as_double("4.9e-324").value == std::numeric_limits<double>::denorm_min());
        CHECK(as_double("2.2250738585072011e-308").value ==
              std::nextafter(std::numeric_limits<double>::min(), 0.0)); // the largest subnormal double
        CHECK(as_double("1e-50").value > 0);
        CHECK(same(float(as_float("1e-50").value), 0.0f)); // below half of float's smallest
        // 17 significant digits name one double
        CHECK(as_double("0.30000000000000004").value == std::nextafter(0.3, 1.0));
        CHECK(as_double("1.7976931348623157e308").value == std::numeric_limits<double>::max());
        CHECK(same(as_double("-0").value, -0.0));
        CHECK(as_double("+1.5").value == 1.5);
        CHECK(as_double(".5").value == 0.5); // as std::from_chars and strtod read it
        CHECK(as_double("5.").value == 5);
        // below the smallest subnormal: a zero of the text's sign
        CHECK(same(as_double("1e-400").value, 0.0));
        CHECK(same(as_double("-1e-400").value, -0.0));

        for (const char* text : {"1e400", "-1e400", "1.7976931348623159e308", "1000e306"}) {
            INFO("the text '" << std::string(text) << "'");
            CHECK(as_double(text).reading == decimal_reading::too_large);
            CHECK(as_float(text).reading == decimal_reading::too_large);
        }
        for (const char* text : {"inf", "-inf", "+inf", "Infinity", "nan", "-nan", "+nan", "NaN", "nan(1)"}) {
            INFO("the text '" << std::string(text) << "'");
            CHECK(as_double(text).reading == decimal_reading::not_finite);
        }
        // nothing skipped but one leading '+': strtod reads a number from the
        // first five (after the blank, before the comma, in hexadecimal,
        // before an exponent without digits), none of which is one
        for (const char* text : {" 1", "1,5", "0x10", "1e", "1e+", "1 ", "", "+", "-", ".", "e5", "+-1", "++1",
                                 "-+1", "1.5.2", "0x1p3", "1_000"}) {
            INFO("the text '" << std::string(text) << "'");
            CHECK(as_double(text).reading == decimal_reading::not_a_number);
            CHECK(as_double(text).value == -7); // left as it was
        }
    });
    CHECK(parsers >= 1);
}

TEST_CASE("read_decimal: 17 significant digits bring any double back exactly")
{
    std::mt19937_64 random(23);
    int checked = 0;
    for_each_parser([&](auto parser, const char* name) {
        using Parser = decltype(parser);
        INFO("parser " << std::string(name));
        for (int k = 0; k < 2000; ++k) {
            const std::uint64_t bits = random();
            double value = 0;
            std::memcpy(&value, &bits, sizeof value);
            if (!std::isfinite(value))
                continue;
            char buffer[64];
            const std::to_chars_result written =
                std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
            REQUIRE(written.ec == std::errc());
            const std::string text(buffer, written.ptr);
            INFO("the text '" << std::string(text) << "'");
            const decimal_result back = read_decimal_with<double, Parser>(text);
            CHECK(back.reading == decimal_reading::number);
            CHECK(same(back.value, value));
            ++checked;
        }
    });
    CHECK(checked > 1000);
}

TEST_CASE("read_decimal<float>: a double halfway between two floats is not rounded again")
{
    // How the text was found: 1 + 2^-24 = 1.000000059604644775390625 lies
    // exactly halfway between the floats 1 and 1 + 2^-23. The text adds
    // 10^-24: it lies above the halfway point, so the float nearest it is
    // 1 + 2^-23, but much closer to it than half the spacing of doubles at 1
    // (2^-53, 1.1e-16), so the double nearest it is the halfway point itself,
    // and that double rounded to float ties to even: 1.
    const std::string text = "1.000000059604644775390626";
    CHECK(c_strtof(text) == 0x1.000002p+0f);
    for_each_parser([&](auto parser, const char* name) {
        using Parser = decltype(parser);
        INFO("parser " << std::string(name));
        const decimal_result nearest_double = read_decimal_with<double, Parser>(text);
        CHECK(nearest_double.value == 0x1.000001p+0);
        CHECK(float(nearest_double.value) == 1.0f); // rounding twice misses
        CHECK(float(read_decimal_with<float, Parser>(text).value) == 0x1.000002p+0f);
        CHECK(float(read_decimal_with<float, Parser>("-" + text).value) == -0x1.000002p+0f);

        // the same below float's normal range: 2^-150 is halfway between 0
        // and the smallest subnormal 2^-149; exactly halfway ties to 0, a
        // digit more goes up
        const std::string halfway = "7.00649232162408535461864791644958065640130970938257885878534141944895541342930300"
                                    "743319094181060791015625e-46";
        CHECK(read_decimal_with<double, Parser>(halfway).value == 0x1p-150);
        CHECK(same(float(read_decimal_with<float, Parser>(halfway).value), 0.0f));
        const std::string above = "7.00649232162408535461864791644958065640130970938257885878534141944895541342930300"
                                  "7433190941810607910156251e-46";
        CHECK(read_decimal_with<double, Parser>(above).value == 0x1p-150);
        CHECK(c_strtof(above) == 0x1p-149f);
        CHECK(float(read_decimal_with<float, Parser>(above).value) == 0x1p-149f);
    });
}

TEST_CASE("read_decimal<float>: the texts exactly at and just above random points halfway between floats")
{
    // For a float f and the next one up g, (f + g) / 2 is a double (25
    // significant bits) written out exactly in decimal: exactly halfway, the
    // float nearest ties to the even one of f and g; with a digit 1 more at
    // the 201st place it is g. Both texts read as that same double, halfway.
    std::mt19937 random(41);
    int cases = 0, naive_misses = 0;
    for_each_parser([&](auto parser, const char* name) {
        using Parser = decltype(parser);
        INFO("parser " << std::string(name));
        for (int k = 0; k < 1000; ++k) {
            const std::uint32_t bits = random() & 0x7fffffffu;
            float f = 0;
            std::memcpy(&f, &bits, sizeof f);
            if (!(f < std::numeric_limits<float>::max()))
                continue; // inf, NaN or the largest (no float above it)
            const float g = std::nextafter(f, std::numeric_limits<float>::infinity());
            const double halfway = (double(f) + double(g)) / 2;
            char buffer[300];
            const std::to_chars_result written =
                std::to_chars(buffer, buffer + sizeof buffer, halfway, std::chars_format::scientific, 200);
            REQUIRE(written.ec == std::errc());
            const std::string exact(buffer, written.ptr);
            const std::size_t e = exact.find('e');
            REQUIRE(e != std::string::npos);
            REQUIRE(exact[e - 1] == '0'); // the expansion ended before the 200th digit: exact
            const std::string above = exact.substr(0, e) + "1" + exact.substr(e);
            std::uint32_t f_bits = 0;
            std::memcpy(&f_bits, &f, sizeof f_bits);
            const float even = (f_bits & 1u) == 0 ? f : g;
            INFO("the texts '" << exact << "' and '" << above << "'");
            CHECK(read_decimal_with<double, Parser>(above).value == halfway);
            CHECK(float(read_decimal_with<float, Parser>(exact).value) == even);
            CHECK(float(read_decimal_with<float, Parser>(above).value) == g);
            CHECK(float(read_decimal_with<float, Parser>("-" + above).value) == -g);
            naive_misses += float(read_decimal_with<double, Parser>(above).value) != g ? 1 : 0;
            ++cases;
        }
    });
    MESSAGE(cases << " halfway points: the double rounded to float misses the float nearest the text above "
                  << naive_misses << " of them");
    CHECK(cases > 900);
    CHECK(naive_misses > cases / 4); // about half: wherever f is the even one
}

TEST_CASE("text_line::number: the hard inputs give the rt::real nearest the text, or the reader's message")
{
    const bool float_real = std::is_same_v<rt::real, float>;
    for (const char* word : {"0.1", "3.4028235e38", "3.40282356e38", "1e-45", "1.4e-45", "1e-50",
                             "0.30000000000000004", "-0", "+1.5", ".5", "5.", "1e-400", "1.000000059604644775390626"}) {
        INFO("the word '" << std::string(word) << "'");
        const number_outcome got = line_number(word);
        CHECK(got.read);
        CHECK(same(got.value, c_nearest_real(word)));
    }
    CHECK(line_number("0.1").value == (float_real ? rt::real(0x1.99999ap-4f) : rt::real(0x1.999999999999ap-4)));
    CHECK(same(line_number("-0").value, -0.0));
    CHECK(line_number("1.000000059604644775390626").value ==
          (float_real ? rt::real(0x1.000002p+0f) : rt::real(0x1.000001p+0)));
    if (float_real) {
        // float's largest is 3.40282347e38 and its shortest text "3.4028235e38"
        // lies above it: a text fits where the float nearest it is finite,
        // below 2^128 - 2^103 = 340282356779733661637539395458142568448
        // (halfway to 2^128, where ties to even go up: the largest is odd)
        const rt::real largest = std::numeric_limits<rt::real>::max();
        CHECK(line_number("3.4028235e38").value == largest);
        CHECK(line_number("3.40282356e38").value == largest);
        CHECK(c_strtof("3.40282356e38") == largest);
        // one below the halfway point: its double is the halfway point itself
        const std::string below_halfway = "340282356779733661637539395458142568447";
        CHECK(read_decimal_with<double, rt::detail::decimal_parser>(below_halfway).value == 0x1.ffffffp+127);
        CHECK(line_number(below_halfway).value == largest);
        for (const char* word : {"340282356779733661637539395458142568448", "3.4028236e38", "3.5e38", "-3.5e38"})
            CHECK(line_number(word).message == "m.obj:1:3: expected a number for the vertex x within +-3.40282e+38, found '" +
                                                    std::string(word).substr(0, 24) + "'; use smaller units");
        CHECK(line_number("1e-45").value == std::numeric_limits<rt::real>::denorm_min());
        CHECK(line_number("1e-50").value == 0);
    } else {
        CHECK(line_number("3.4028236e38").value == c_strtod("3.4028236e38"));
        CHECK(line_number("4.9e-324").value == std::numeric_limits<double>::denorm_min());
        CHECK(line_number("2.2250738585072011e-308").value == std::nextafter(std::numeric_limits<double>::min(), 0.0));
    }
    CHECK(line_number("1e400").message.find("m.obj:1:3: expected a number for the vertex x within +-") == 0);
    CHECK(line_number("1,5").message == "m.obj:1:3: expected a number for the vertex x, found '1,5'");
    CHECK(line_number("0x10").message == "m.obj:1:3: expected a number for the vertex x, found '0x10'");
    CHECK(line_number("1e").message == "m.obj:1:3: expected a number for the vertex x, found '1e'");
    CHECK(line_number("+-1").message == "m.obj:1:3: expected a number for the vertex x, found '+-1'");
    CHECK(line_number("inf").message ==
          "m.obj:1:3: expected a finite number for the vertex x, found 'inf'; NaN and inf are not allowed");
}

TEST_CASE("read_decimal: a locale with a decimal comma changes nothing")
{
    // strtod and std::stod read the decimal point of the C locale: "0.5"
    // stops at the '.' where it is a comma. Both locales come back when the
    // case ends, whatever happens in it.
    struct restore_locales {
        std::locale cpp = std::locale();
        std::string c = std::setlocale(LC_ALL, nullptr);
        ~restore_locales()
        {
            std::locale::global(cpp);
            std::setlocale(LC_ALL, c.c_str());
        }
    } restore;
    // the C locale: the first installed one with a decimal comma
    const char* comma_name = nullptr;
    for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "de_DE", "fr_FR.UTF-8", "German_Germany.1252"}) {
        if (std::setlocale(LC_ALL, name) && std::localeconv()->decimal_point[0] == ',') {
            comma_name = name;
            break;
        }
    }
    // the C++ global locale: the same where the standard library knows it by
    // name (which sets the C locale again), else a decimal comma of its own
    std::locale cpp_comma(std::locale::classic(), new decimal_comma);
    if (comma_name) {
        try {
            cpp_comma = std::locale(comma_name);
        } catch (const std::runtime_error&) {
        }
    }
    std::locale::global(cpp_comma);
    if (comma_name) {
        MESSAGE("the C locale is " << std::string(comma_name));
        const std::string half = "0.5";
        char* end = nullptr;
        CHECK(std::strtod(half.c_str(), &end) == 0); // the C library's parser fails
        CHECK(end == half.c_str() + 1);
    } else {
        std::setlocale(LC_ALL, restore.c.c_str());
        MESSAGE("no installed locale has a decimal comma (de_DE.UTF-8 and others): only the C++ locale has one "
                "here, the C locale stays as it was");
    }
    CHECK(std::use_facet<std::numpunct<char>>(std::locale()).decimal_point() == ',');
    for_each_parser([](auto parser, const char* name) {
        using Parser = decltype(parser);
        INFO("parser " << std::string(name));
        CHECK(read_decimal_with<rt::real, Parser>("0.5").value == 0.5);
        CHECK(read_decimal_with<rt::real, Parser>("-1.25e-1").value == -0.125);
        CHECK(read_decimal_with<rt::real, Parser>("0,5").reading == decimal_reading::not_a_number);
    });
    CHECK(line_number("0.5").value == 0.5f);
    CHECK(line_number("0,5").message == "m.obj:1:3: expected a number for the vertex x, found '0,5'");
}

TEST_CASE("the scene reader and the OBJ reader read a number alike: the same value or the same message")
{
    // float's limits in both (a scene number must fit rt::real, an OBJ number
    // rt::real and tinyobjloader's float); with RT_USE_DOUBLE only the words
    // that fit a float are compared
    const bool same_limit = double(std::numeric_limits<rt::real>::max()) == rt::detail::obj_line::largest_number();
    std::vector<std::string> words = {"1.5", "-0.25e1", "+2", "nan", "inf", "abc", "12x", "1e-400", "0.5",
                                      "+-1", "0x10", "1,5", ".5", "5.", "1e"};
    if (same_limit) {
        words.push_back("1e39");
        words.push_back("1e400");
    }
    for (const std::string& word : words) {
        const std::string text = "x " + word;
        const std::string file = "f";
        const rt::source_location where{file, 1};
        rt::statement scene(file, 1, rt::detail::tokenize(text, where), int(text.size()) + 1);
        const std::vector<rt::line_piece> pieces = {{0, 1, 1}};
        rt::detail::obj_line obj(file, pieces, text.data(), text.data() + text.size());
        obj.word();
        const std::string from_scene = outcome([&] { return scene.number("the value"); });
        const std::string from_obj = outcome([&] { return obj.number("the value"); });
        INFO("the word '" << word << "': a scene statement gives \"" << from_scene << "\", an OBJ line \"" << from_obj << "\"");
        CHECK(from_scene == from_obj);
    }
}

TEST_CASE("text_line: a line continued with a backslash keeps each piece's line and column")
{
    // "v 1 2 \\\n3" is read as the logical line "v 1 2  3": its second piece
    // starts at offset 7, on line 5, column 1
    const std::string text = "v 1 2  x";
    const std::vector<rt::line_piece> pieces = {{0, 4, 1}, {7, 5, 1}};
    const std::string file = "m.obj";
    rt::text_line line(file, pieces, text.data(), text.data() + text.size());
    CHECK(line.word() == "v");
    CHECK(line.number("the vertex x") == 1);
    CHECK(line.number("the vertex y") == 2);
    const rt::source_location at = line.here();
    CHECK(at.line == 5);
    CHECK(at.column == 1);
    CHECK(std::string(line.unexpected("a number for the vertex z").what()) ==
          "m.obj:5:1: expected a number for the vertex z, found 'x'");
}

TEST_CASE("for_each_line: LF, CR LF and a lone CR end a line, a byte order mark is skipped, a backslash continues")
{
    const std::string text = "\xEF\xBB\xBF" "a 1\r\nb 2\rc \\\n3\nd";
    std::vector<std::string> seen;
    std::string normalised;
    const std::string file = "t";
    rt::detail::for_each_line<rt::text_line>(text, file, [&](rt::text_line& line, int number) {
        std::string words = std::to_string(number) + ":";
        while (!line.done()) {
            const int at = line.here().line; // where the word starts: before word() moves on
            words += " " + line.word() + "@" + std::to_string(at);
        }
        seen.push_back(words);
    }, &normalised);
    std::string all;
    for (const std::string& words : seen)
        all += (all.empty() ? "" : " | ") + words;
    CHECK(all == "1: a@1 1@1 | 2: b@2 2@2 | 3: c@3 3@4 | 5: d@5");
    CHECK(normalised == "a 1\nb 2\nc  3\nd\n");
}

TEST_CASE("tokenize: scene words, \"quoted strings\" and comments, with their columns")
{
    const rt::source_location where{"s.scene", 3};
    const std::vector<rt::token> tokens = rt::detail::tokenize("mesh \"my model.obj\" scale 2#comment \"x", where);
    REQUIRE(tokens.size() == 4);
    CHECK(tokens[0].text == "mesh");
    CHECK(tokens[1].text == "my model.obj");
    CHECK(tokens[1].column == 6);
    CHECK(tokens[2].text == "scale");
    CHECK(tokens[3].text == "2");
    CHECK(tokens[3].column == 27);
    CHECK(rt::detail::tokenize("   # only a comment", where).empty());

    const std::string unclosed = outcome([&] { return rt::detail::tokenize("mesh \"a b", where).size(); });
    CHECK(unclosed == "s.scene:3:6: expected a closing '\"', found the end of the line");
    const std::string binary = outcome([&] { return rt::detail::tokenize("mesh a\x01", where).size(); });
    CHECK(binary == "s.scene:3:7: expected plain text (ASCII or UTF-8), found a byte of value 1; is this a scene file?");
}
