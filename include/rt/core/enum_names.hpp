// enum_names.hpp - one way to name the values of rt's option enums (sampler,
// filter, tone map, debug image, accelerator, projection): a table of (value, name) pairs
// per enum, read both ways. Every command line and scene word goes through it,
// so a name is spelled in exactly one place.
//
//     inline constexpr enum_name<filter_kind> filter_names[] = {{filter_kind::box, "box"}, ...};
//     std::optional<filter_kind> k = value_named(filter_names, "tent");   // filter_kind::tent
//     const char* n = name_in(filter_names, filter_kind::box);            // "box"
#pragma once

#include <cstddef>
#include <cstring>
#include <optional>
#include <string>

namespace rt {

namespace detail {

/// One value of an enum and the word that names it.
template <class Enum>
struct enum_name {
    Enum value;
    const char* name;
};

/// The value `name` names in `table`, or nothing (the caller says what was expected).
template <class Enum, std::size_t N>
std::optional<Enum> value_named(const enum_name<Enum> (&table)[N], const std::string& name)
{
    for (const enum_name<Enum>& entry : table)
        if (name == entry.name)
            return entry.value;
    return std::nullopt;
}

/// The name of `value` in `table`; a value the table lacks gets the first
/// entry's name (the enum's default).
template <class Enum, std::size_t N>
const char* name_in(const enum_name<Enum> (&table)[N], Enum value)
{
    for (const enum_name<Enum>& entry : table)
        if (entry.value == value)
            return entry.name;
    return table[0].name;
}

/// The names of `table` as "a, b, c" for messages and --help.
template <class Enum, std::size_t N>
std::string names_listed(const enum_name<Enum> (&table)[N])
{
    std::string list;
    for (const enum_name<Enum>& entry : table)
        list += (list.empty() ? "" : ", ") + std::string(entry.name);
    return list;
}

} // namespace detail

} // namespace rt
