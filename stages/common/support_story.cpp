// Printing a pixel's story (pixel_story.hpp) as text and as JSON, compiled once.
#include "pixel_story.hpp"

#include <cmath>
#include <cstdio>
#include <variant>

#include <rt/core/error.hpp>

namespace stage {

namespace {

std::string number(double x)
{
    if (std::isinf(x))
        return x > 0 ? "inf" : "-inf";
    char text[40];
    std::snprintf(text, sizeof text, "%.9g", x);
    return text;
}

std::string json_number(double x)
{
    return std::isfinite(x) ? number(x) : "null"; // JSON has no infinity: null stands for it
}

template <class Vector>
std::string triple(const Vector& v)
{
    return "(" + number(double(v.x)) + ", " + number(double(v.y)) + ", " + number(double(v.z)) + ")";
}

std::string color_text(const rt::color& c)
{
    return "(" + number(double(c.r)) + ", " + number(double(c.g)) + ", " + number(double(c.b)) + ")";
}

template <class Vector>
std::string json_triple(const Vector& v)
{
    return "[" + json_number(double(v.x)) + ", " + json_number(double(v.y)) + ", " + json_number(double(v.z)) + "]";
}

std::string json_color(const rt::color& c)
{
    return "[" + json_number(double(c.r)) + ", " + json_number(double(c.g)) + ", " + json_number(double(c.b)) + "]";
}

std::string json_string(const std::string& text)
{
    std::string out = "\"";
    for (const char ch : text) {
        if (ch == '"' || ch == '\\') {
            out += '\\';
            out += ch;
        } else if (static_cast<unsigned char>(ch) < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", unsigned(static_cast<unsigned char>(ch)));
            out += escaped;
        } else {
            out += ch;
        }
    }
    return out + "\"";
}

/// "sphere", "triangle" or "mesh" for the scene's shape `index`.
std::string shape_kind(const rt::scene& sc, std::uint32_t index)
{
    if (index >= sc.shapes.size())
        return "unknown";
    const rt::shape& item = sc.shapes[index];
    if (std::holds_alternative<rt::sphere>(item))
        return "sphere";
    if (std::holds_alternative<rt::triangle>(item))
        return "triangle";
    return "mesh";
}

std::string shape_text(const rt::scene& sc, const rt::hit_record& rec)
{
    std::string text = "shape " + std::to_string(rec.shape) + " (" + shape_kind(sc, rec.shape);
    if (shape_kind(sc, rec.shape) == "mesh")
        text += ", triangle " + std::to_string(rec.primitive);
    return text + ")";
}

std::string interval(const query_record& q)
{
    return "[" + number(double(q.tmin)) + ", " + number(double(q.tmax)) + "]";
}

} // namespace

void place_pixel(story& s, int column, int row, int nx, int ny)
{
    if (column < 0 || column >= nx || row < 0 || row >= ny)
        throw rt::error("--pixel: expected a column from 0 to " + std::to_string(nx - 1) + " and a row from 0 to " +
                        std::to_string(ny - 1) + " (the image is " + std::to_string(nx) + "x" + std::to_string(ny) +
                        "), found " + std::to_string(column) + " " + std::to_string(row));
    s.column = column;
    s.row = row;
    s.i = column;
    s.j = ny - 1 - row; // the book counts rows from the bottom
}

void print_story(std::ostream& out, const story& s, const rt::scene& sc)
{
    out << s.program << ": pixel " << s.column << " " << s.row
        << " (column from the left, row from the top; the book's i = " << s.i << ", j = " << s.j
        << " from the bottom)\n";
    out << "camera ray: origin " << triple(s.camera.origin) << ", direction " << triple(s.camera.direction) << "\n";
    for (std::size_t k = 0; k < s.queries.size(); ++k) {
        const query_record& q = s.queries[k];
        const bool closest = q.what == query_record::kind::closest;
        out << "[" << k << "] " << q.role << ": " << (closest ? "closest hit" : "any hit") << " in t "
            << interval(q);
        if (q.role != "camera")
            out << ", origin " << triple(q.r.origin) << ", direction " << triple(q.r.direction);
        if (!closest && std::isfinite(double(q.tmax)))
            out << ", ends at " << triple(q.r.at(q.tmax));
        out << "\n";
        if (!q.hit) {
            out << "    " << (closest ? "missed: the background " + color_text(sc.background)
                                      : std::string("nothing in the way: the light is visible"))
                << "\n";
            continue;
        }
        if (!closest) {
            out << "    blocked by " << shape_text(sc, q.rec) << " at t " << number(double(q.rec.t)) << ", point "
                << triple(q.rec.point) << "\n";
            continue;
        }
        out << "    hit " << shape_text(sc, q.rec) << " at t " << number(double(q.rec.t)) << "\n"
            << "    point " << triple(q.rec.point) << "\n"
            << "    geometric normal " << triple(q.rec.geometric_normal) << ", shading normal "
            << triple(q.rec.normal) << ", " << (q.rec.front_face ? "front face" : "back face") << "\n"
            << "    material " << q.rec.material << "\n";
        std::size_t hit_index = 0;
        for (std::size_t m = 0; m < k; ++m)
            hit_index += s.queries[m].what == query_record::kind::closest && s.queries[m].hit ? 1 : 0;
        if (hit_index < s.ambient.size())
            out << "    ambient ka Ia " << color_text(s.ambient[hit_index]) << "\n";
        for (const light_term& t : s.lights) {
            if (t.query != k)
                continue;
            out << "    light " << t.light << ": l " << triple(t.sample.l) << ", distance "
                << number(double(t.sample.distance)) << ", I " << color_text(t.sample.intensity);
            if (t.behind)
                out << "; behind the surface: no light, no shadow ray\n";
            else if (!t.visible)
                out << "; in shadow (query [" << *t.shadow_query << "]): no light\n";
            else
                out << (t.shadow_query ? "; visible (query [" + std::to_string(*t.shadow_query) + "])" : std::string())
                    << "; Blinn-Phong term " << color_text(t.term) << "\n";
        }
    }
    out << "color (linear) " << color_text(s.linear) << "\n";
    for (const auto& [name, value] : s.values)
        out << name << " " << value << "\n";
}

void print_story_json(std::ostream& out, const story& s, const rt::scene& sc)
{
    out << "{\n  \"program\": " << json_string(s.program) << ",\n";
    out << "  \"pixel\": {\"column\": " << s.column << ", \"row\": " << s.row << ", \"i\": " << s.i
        << ", \"j\": " << s.j << "},\n";
    out << "  \"camera\": {\"origin\": " << json_triple(s.camera.origin)
        << ", \"direction\": " << json_triple(s.camera.direction) << "},\n";
    out << "  \"queries\": [";
    for (std::size_t k = 0; k < s.queries.size(); ++k) {
        const query_record& q = s.queries[k];
        out << (k ? ",\n" : "\n") << "    {\"role\": " << json_string(q.role) << ", \"kind\": \""
            << (q.what == query_record::kind::closest ? "closest" : "any") << "\", \"origin\": "
            << json_triple(q.r.origin) << ", \"direction\": " << json_triple(q.r.direction)
            << ", \"tmin\": " << json_number(double(q.tmin)) << ", \"tmax\": " << json_number(double(q.tmax))
            << ", \"end\": "
            << (std::isfinite(double(q.tmax)) ? json_triple(q.r.at(q.tmax)) : std::string("null"))
            << ", \"hit\": " << (q.hit ? "true" : "false");
        if (q.hit)
            out << ", \"shape\": " << q.rec.shape << ", \"shape_kind\": " << json_string(shape_kind(sc, q.rec.shape))
                << ", \"primitive\": " << q.rec.primitive << ", \"t\": " << json_number(double(q.rec.t))
                << ", \"point\": " << json_triple(q.rec.point)
                << ", \"geometric_normal\": " << json_triple(q.rec.geometric_normal)
                << ", \"normal\": " << json_triple(q.rec.normal)
                << ", \"front_face\": " << (q.rec.front_face ? "true" : "false")
                << ", \"material\": " << q.rec.material;
        out << "}";
    }
    out << "\n  ],\n  \"ambient\": [";
    for (std::size_t k = 0; k < s.ambient.size(); ++k)
        out << (k ? ", " : "") << json_color(s.ambient[k]);
    out << "],\n  \"lights\": [";
    for (std::size_t k = 0; k < s.lights.size(); ++k) {
        const light_term& t = s.lights[k];
        out << (k ? ",\n" : "\n") << "    {\"query\": " << t.query << ", \"light\": " << t.light
            << ", \"l\": " << json_triple(t.sample.l) << ", \"distance\": " << json_number(double(t.sample.distance))
            << ", \"intensity\": " << json_color(t.sample.intensity)
            << ", \"behind\": " << (t.behind ? "true" : "false") << ", \"visible\": " << (t.visible ? "true" : "false")
            << ", \"shadow_query\": " << (t.shadow_query ? std::to_string(*t.shadow_query) : std::string("null"))
            << ", \"term\": " << json_color(t.term) << "}";
    }
    out << (s.lights.empty() ? "" : "\n  ") << "],\n  \"color\": " << json_color(s.linear) << ",\n  \"values\": {";
    for (std::size_t k = 0; k < s.values.size(); ++k)
        out << (k ? ", " : "") << json_string(s.values[k].first) << ": " << json_string(s.values[k].second);
    out << "}\n}\n";
}

} // namespace stage
