// mtl_reader.hpp - the material libraries (MTL files) of an OBJ mesh (stage 04).
//
// An MTL file ("Material Library Files (.mtl)", Wavefront's Advanced
// Visualizer documentation) is read here, line by line with obj_line's checks:
//   newmtl name        a material; the statements below it describe it
//   Ka/Kd/Ks r [g b]   ambient, diffuse and specular colors ("Kd r" is r r r)
//   Ke r [g b]         the emitted radiance Le (stage 11's area lights)
//   Ns exponent        the Phong exponent      illum model   0 to 10
// everything else (Ni, d, maps) is skipped, its numbers checked. The
// materials are then handed to tinyobjloader by name (mtl_names_reader), so it
// never parses an MTL file itself and its material ids index the entries read
// here. obj_loader.hpp maps them to rt::material.
//
//     std::vector<rt::detail::mtl_entry> entries;
//     rt::detail::read_mtl("models/box.mtl", {}, std::uintmax_t(1) << 32, entries);
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "../core/error.hpp"
#include "../scene/material.hpp"
#include "obj_line.hpp"
#include "../system/path_text.hpp"
#include "text_line.hpp"

namespace rt {
namespace detail {

/// One MTL material as read here, with what tinyobjloader would not tell: which
/// statements were present.
struct mtl_entry {
    material value;
    bool has_ka = false;
    bool has_ns = false;
    int illum = 2;
};

/// Parses one MTL file into `entries` (see the top of this file and of obj_loader.hpp).
inline void read_mtl(const std::filesystem::path& path, const source_location& named_at, std::uintmax_t max_bytes,
                     std::vector<mtl_entry>& entries)
{
    const std::string name = utf8_text(path);
    const std::string text = read_text(path, "the material library", max_bytes, named_at);
    for_each_line<obj_line>(text, name, [&](obj_line& line, int) {
        if (line.done())
            return;
        const source_location keyword_at = line.here();
        const std::string keyword = line.word();
        if (keyword == "newmtl") {
            if (line.done())
                throw line.unexpected("a material name after newmtl");
            mtl_entry entry;
            entry.value.name = line.word();
            entries.push_back(entry);
            return;
        }
        const bool is_color = keyword == "Ka" || keyword == "Kd" || keyword == "Ks" || keyword == "Ke";
        const bool known = is_color || keyword == "Ns" || keyword == "illum";
        if (!known) { // Ni, d, Tr, maps ...: not used by rt, but their numbers must fit a float too
            line.check_number_words(false);
            return;
        }
        if (entries.empty())
            throw make_error(keyword_at, "'newmtl name' before '" + printable(keyword, 24) + "'", "'" + printable(keyword, 24) + "' first",
                             "every material starts with newmtl");
        mtl_entry& entry = entries.back();
        if (is_color) {
            if (!line.done() && !line.number_follows())
                throw line.unexpected("an RGB color for " + keyword, "rt reads 'K? r g b' (not spectral or xyz)");
            color c;
            for (int channel = 0; channel < 3; ++channel) {
                if (channel == 1 && line.done()) { // "Kd r" means r r r
                    c.g = c.b = c.r;
                    break;
                }
                const source_location at = line.here();
                const real value = line.number(keyword + " " + "rgb"[channel]);
                if (value < 0)
                    throw make_error(at, "a non-negative " + keyword, std::to_string(value),
                                     "colors cannot be negative");
                c[channel] = float(value);
            }
            if (keyword == "Ka") {
                entry.value.ka = c;
                entry.has_ka = true;
            } else if (keyword == "Kd") {
                entry.value.kd = c;
            } else if (keyword == "Ke") {
                entry.value.emission = c;
            } else {
                entry.value.ks = c;
            }
        } else if (keyword == "Ns") {
            const source_location at = line.here();
            entry.value.p = line.number("the Phong exponent Ns");
            if (entry.value.p < 0)
                throw make_error(at, "a non-negative Ns", std::to_string(entry.value.p));
            entry.has_ns = true;
        } else {
            const source_location at = line.here();
            const real model = line.number("the illumination model");
            if (!(model >= 0 && model <= 10 && model == std::floor(model)))
                throw make_error(at, "an illumination model 0 to 10", std::to_string(model));
            entry.illum = int(model);
        }
        if (!line.done())
            throw line.unexpected("the end of the line", "'" + keyword + "' takes fewer numbers");
    });
}

/// Hands the MTL materials read above to tinyobjloader by name, so that its
/// material ids index `entries` (it then never parses an MTL file itself).
class mtl_names_reader : public tinyobj::MaterialReader {
public:
    explicit mtl_names_reader(const std::vector<mtl_entry>& entries) : entries_(entries) {}

    bool operator()(const std::string&, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string*, std::string*) override
    {
        if (done_)
            return true;
        done_ = true;
        for (const mtl_entry& entry : entries_) {
            tinyobj::material_t m{}; // value-initialised: its plain fields are zero, not indeterminate
            m.name = entry.value.name;
            if (names->count(m.name) == 0) // the first material of a name wins, as in the check
                (*names)[m.name] = int(materials->size());
            materials->push_back(m);
        }
        return true;
    }

private:
    const std::vector<mtl_entry>& entries_;
    bool done_ = false;
};

} // namespace detail
} // namespace rt
