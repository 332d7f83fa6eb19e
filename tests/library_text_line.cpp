// library_text_line.cpp - the one tokenizer of scene, OBJ and MTL files
// (include/rt/text_line.hpp, text_file.hpp): numbers read alike by every
// reader, columns across continued lines, scene tokens with quotes and
// comments. No exercise is called.
#include "rt_doctest.hpp"

#include <limits>
#include <string>
#include <vector>

#include <rt/obj_line.hpp>
#include <rt/scene_statement.hpp>
#include <rt/text_file.hpp>
#include <rt/text_line.hpp>

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
    // beyond double both ways: from_chars says only "out of range", the
    // decimal exponent of the first significant digit tells which
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

TEST_CASE("the scene reader and the OBJ reader read a number alike: the same value or the same message")
{
    // float's limits in both (a scene number must fit rt::real, an OBJ number
    // rt::real and tinyobjloader's float); with RT_USE_DOUBLE only the words
    // that fit a float are compared
    const bool same_limit = double(std::numeric_limits<rt::real>::max()) == rt::detail::obj_line::largest_number();
    std::vector<std::string> words = {"1.5", "-0.25e1", "+2", "nan", "inf", "abc", "12x", "1e-400", "0.5"};
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
