// fuzz_scene_obj.cpp - libFuzzer target: a scene file with the OBJ and MTL
// files it names, loaded through rt::load_scene (and tinyobjloader behind
// rt::load_obj).
//
// The input is up to three parts separated by a line "%%":
//     scene text \n%%\n OBJ text \n%%\n MTL text
// written to s.scene, m.obj and m.mtl in a scratch folder. An empty scene part
// stands for "mesh m.obj", so inputs that are mostly OBJ stay short.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include <rt/input/scene_loader.hpp>

#include "fuzz_support.hpp"

namespace {

/// Splits off the text before the first separator; `rest` keeps what follows.
std::string take_part(std::string& rest)
{
    static const std::string separator = "\n%%\n";
    const std::size_t at = rest.find(separator);
    if (at == std::string::npos) {
        std::string part;
        part.swap(rest);
        return part;
    }
    std::string part = rest.substr(0, at);
    rest.erase(0, at + separator.size());
    return part;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const fuzz::scratch_folder folder;
    std::string rest(reinterpret_cast<const char*>(data), size);
    std::string scene_text = take_part(rest);
    const std::string obj_text = take_part(rest);
    const std::string mtl_text = rest;
    if (scene_text.empty())
        scene_text = "mesh m.obj\n";
    folder.write("s.scene", scene_text);
    folder.write("m.obj", obj_text);
    folder.write("m.mtl", mtl_text);
    // warnings (missing materials, polygons not simple) are lines of the same
    // form as the errors: each is checked like one
    std::ostringstream warnings;
    rt::load_options options;
    options.obj.warnings = &warnings;
    try {
        const rt::scene s = rt::load_scene(folder.path() / "s.scene", options);
        (void)s;
    } catch (const rt::error& e) {
        fuzz::check_message(e);
    }
    std::istringstream lines(warnings.str());
    for (std::string line; std::getline(lines, line);)
        fuzz::check_message(rt::error(line));
    return 0;
}
