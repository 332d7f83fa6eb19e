// fuzz_scene.cpp - libFuzzer target: the scene parser, from a string.
//
// The input is the text of a scene file, parsed by rt::load_scene_from_string
// with mesh paths relative to an empty scratch folder (so a `mesh` statement
// exercises the missing-file path; fuzz_scene_obj covers meshes that exist).
#include <cstddef>
#include <cstdint>
#include <string>

#include <rt/input/scene_loader.hpp>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const fuzz::scratch_folder folder;
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const rt::scene s = rt::load_scene_from_string(text, "fuzz.scene", folder.path());
        (void)s;
    } catch (const rt::error& e) {
        fuzz::check_message(e);
    }
    return 0;
}
