// path_text.hpp - a path as UTF-8 text, and UTF-8 text as a path, alike on
// every system.
//
//     const std::string shown = rt::detail::utf8_text(path);             // for a message
//     const std::filesystem::path mesh = rt::detail::utf8_path(written); // a name read from a file
//
// rt's text is UTF-8: scene, OBJ and MTL files, and every message. A
// std::filesystem::path built from a std::string, or turned into one by
// .string(), goes through the native narrow encoding (C++17 [fs.path.type.cvt]):
// on POSIX the bytes themselves, on Windows the active code page, where an
// accented name turns into other characters and a name outside the code page
// cannot be written at all. u8path and u8string convert UTF-8 explicitly
// ([fs.path.factory], [fs.path.native.obs]); on POSIX they leave the bytes as
// they are, so nothing changes there. C++20 deprecates u8path and makes u8string return a
// std::u8string, so with char8_t both helpers go through std::u8string.
#pragma once

#include <filesystem>
#include <string>

namespace rt {
namespace detail {

/// `path` as UTF-8 text (for a message, or a key compared with others), its
/// names separated by '/' on every system (the generic format,
/// [fs.path.generic.obs]; Windows takes '/' too), so that a message reads the
/// same everywhere: "obj/cube.mtl:2:6", never "obj\cube.mtl:2:6" on Windows.
inline std::string utf8_text(const std::filesystem::path& path)
{
    const auto text = path.generic_u8string(); // std::string in C++17, std::u8string with char8_t
    return std::string(text.begin(), text.end());
}

/// The path that UTF-8 `text` names (a file name read from a scene or OBJ file).
inline std::filesystem::path utf8_path(const std::string& text)
{
#if defined(__cpp_lib_char8_t)
    return std::filesystem::path(std::u8string(text.begin(), text.end()));
#else
    return std::filesystem::u8path(text);
#endif
}

} // namespace detail
} // namespace rt
