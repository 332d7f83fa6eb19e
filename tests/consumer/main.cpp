// A consumer of rt: loads a scene, generates rays, writes a PNG.
#include <cstdio>
#include <filesystem>

#include <rt/rt.hpp>

int count_rays(const rt::scene& s); // second_unit.cpp: rt in two translation units links

int main(int argc, char** argv)
{
    const std::filesystem::path out = argc > 1 ? argv[1] : "consumer.png";
    try {
        const rt::scene s = rt::load_scene_from_string("image 32 16\ncamera perspective eye 0 0 3 fov 60\nsphere\n");
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
        rt::save_image(out, rt::render_ray_directions(gen));
        std::printf("consumer: real is %zu bytes, %d rays, wrote %s\n", sizeof(rt::real), count_rays(s),
                    out.string().c_str());
    } catch (const rt::error& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
    return 0;
}
