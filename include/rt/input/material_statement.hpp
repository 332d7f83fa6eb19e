// material_statement.hpp - the material statement of a scene file, and the
// lookup of a material by name that shapes and meshes make (scene_loader.hpp
// reads the file; docs/scene-format.md describes the statement).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../scene/material.hpp"
#include "../scene/scene.hpp"
#include "scene_statement.hpp"
#include "../core/vec.hpp"

namespace rt {
namespace detail {

/// The index of the declared material the line names next; an error naming
/// the nearest declared name when there is none.
inline int find_material(const scene& s, statement& line)
{
    const std::string name = line.word("a material name");
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name)
            return int(i);
    std::vector<std::string> known;
    for (const material& m : s.materials)
        known.push_back(m.name);
    throw make_error(line.last(), "a declared material", "unknown material " + found_text(name),
                     nearest_hint(name, known) + " (declare materials before using them)");
}

/// Reads `material name [ka rgb] [kd rgb] [ks rgb] [p n] [km rgb] [ior n]
/// [attenuation rgb] [glossy a]`; `declared` are the materials before it.
inline material read_material(statement& line, const std::vector<material>& declared)
{
    material m;
    m.name = line.word("a material name");
    for (const material& other : declared)
        if (other.name == m.name)
            throw make_error(line.last(), "a new material name", "a second material " + found_text(m.name),
                             "material names must be unique");
    bool ambient_given = false, diffuse_given = false;
    source_location km_at{}, attenuation_at{}, glossy_at{};
    bool km_given = false, attenuation_given = false, glossy_given = false;
    line.options({"ka", "kd", "ks", "p", "km", "ior", "attenuation", "glossy", "emission"},
                 [&](const std::string& option) {
        if (option == "ka") {
            m.ka = line.rgb("ka");
            ambient_given = true;
        } else if (option == "kd") {
            m.kd = line.rgb("kd");
            diffuse_given = true;
        } else if (option == "ks")
            m.ks = line.rgb("ks");
        else if (option == "km") {
            km_at = line.last();
            km_given = true;
            m.km = line.rgb("km");
        } else if (option == "ior") {
            const source_location where = line.here();
            m.ior = line.number("the index of refraction ior");
            if (!(m.ior >= 1 && m.ior <= 10))
                throw make_error(where, "an index of refraction from 1 to 10", detail::short_number(double(m.ior)),
                                 "glass is 1.5, water 1.33, diamond 2.42");
        } else if (option == "glossy") {
            glossy_at = line.last();
            glossy_given = true;
            const source_location where = line.here();
            m.glossy = line.number("the glossy blur a");
            if (!(m.glossy >= 0 && m.glossy <= 4))
                throw make_error(where, "a glossy blur from 0 to 4", detail::short_number(double(m.glossy)),
                                 "it is the side of the square of perturbed directions: 0.1 is brushed metal");
        } else if (option == "emission") {
            m.emission = line.rgb("emission");
        } else if (option == "attenuation") {
            attenuation_at = line.last();
            attenuation_given = true;
            m.attenuation = line.rgb("attenuation");
        } else {
            const source_location where = line.here();
            m.p = line.number("Phong exponent p");
            if (m.p < 0)
                throw make_error(where, "a non-negative Phong exponent", detail::short_number(double(m.p)));
        }
    });
    if (is_dielectric(m) && km_given)
        throw make_error(km_at, "either km (a mirror) or ior (a dielectric)", "both",
                         "a dielectric reflects by the Fresnel equations: drop km");
    if (!is_dielectric(m) && attenuation_given)
        throw make_error(attenuation_at, "attenuation only with ior", "attenuation without ior",
                         "attenuation is absorption inside a dielectric: add ior (glass 1.5)");
    if (glossy_given && !(m.km.r > 0 || m.km.g > 0 || m.km.b > 0))
        throw make_error(glossy_at, "glossy only with km", "glossy without a mirror",
                         "glossy blurs a mirror's reflection: add km (0.8 0.8 0.8)");
    if (is_dielectric(m) && !diffuse_given)
        m.kd = color(0.0f); // clear glass unless the file says otherwise
    if (!ambient_given)
        m.ka = m.kd;
    return m;
}

} // namespace detail
} // namespace rt
