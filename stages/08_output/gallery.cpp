// stage08_gallery - the comparison picture of docs/renderer.md: the samplers
// and the reconstruction filters on analytic test patterns, one picture.
//
//     stage08_gallery docs/images/08-samplers-filters.png
//
// Row 1: a zone plate, 16 samples per pixel, box filter, with the samplers
//        center (1 sample), grid, random, jittered, halton.
// Row 2: the same zone plate, jittered 16 spp, with the filters box, tent,
//        gaussian, mitchell.
// Row 3: a slanted edge (15 degrees from the vertical), the samplers of row 1
//        at 16 spp, a 16 x 16 pixel crop magnified 8 times.
// The zone plate L = (1 + cos(pi r^2 / w)) / 2 (w the panel size, r in pixels
// from the centre) has the local frequency r / w cycles per pixel: beyond the
// circle r = w / 2 it is above the Nyquist limit, and what appears there
// (rings centred elsewhere) is aliasing.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <ostream>
#include <string>
#include <vector>

#include <rt/system/atomic_file.hpp>
#include <rt/output/encoding.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/core/image.hpp>
#include <rt/output/encoded_output.hpp>
#include <rt/output/image_io.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/sampler.hpp>

#include "stage_main.hpp"

namespace {

const double pi = 3.14159265358979323846;

rt::ray film_ray(rt::real x, rt::real y)
{
    return rt::ray{rt::vec3(x, y, 0), rt::vec3(0, 0, -1)};
}

rt::image zone_plate(int size, rt::sampler_kind sampler, int spp, rt::filter_kind filter)
{
    rt::render_options options;
    options.width = options.height = size;
    options.sampler = sampler;
    options.samples_per_pixel = spp;
    options.reconstruction = rt::make_filter(filter);
    options.seed = 8;
    const double c = size / 2.0, w = size;
    return rt::render(options, film_ray, [=](const rt::ray& r, rt::sample_context&) {
               const double dx = double(r.origin.x) - c, dy = double(r.origin.y) - c;
               return rt::color(float(0.5 + 0.5 * std::cos(pi * (dx * dx + dy * dy) / w)));
           }).pixels;
}

/// A crop of `crop` x `crop` pixels of a slanted edge, magnified `zoom` times (nearest pixel).
rt::image slanted_edge(int crop, int zoom, rt::sampler_kind sampler, int spp)
{
    rt::render_options options;
    options.width = options.height = crop;
    options.sampler = sampler;
    options.samples_per_pixel = spp;
    options.seed = 8;
    const double angle = 15 * pi / 180, a = std::cos(angle), b = -std::sin(angle), c = crop / 2.0;
    const rt::image small = rt::render(options, film_ray, [=](const rt::ray& r, rt::sample_context&) {
                                return rt::color(a * (double(r.origin.x) - c) + b * (double(r.origin.y) - c) < 0 ? 1.0f
                                                                                                                  : 0.0f);
                            }).pixels;
    rt::image big(crop * zoom, crop * zoom);
    for (int y = 0; y < big.height; ++y)
        for (int x = 0; x < big.width; ++x)
            big.at(x, y) = small.at(x / zoom, y / zoom);
    return big;
}

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage08_gallery", [&] {
        if (argc != 2 || std::string(argv[1]) == "--help") {
            std::cerr << "usage: stage08_gallery OUTPUT.png\n";
            return argc == 2 ? 0 : 2;
        }
        const std::filesystem::path output = stage::file_argument(argv[1]);
        rt::check_image_output(output);
        const int panel = 128, gap = 4, spp = 16;
        const rt::sampler_kind samplers[] = {rt::sampler_kind::center, rt::sampler_kind::grid, rt::sampler_kind::random,
                                             rt::sampler_kind::jittered, rt::sampler_kind::halton};
        const rt::filter_kind filters[] = {rt::filter_kind::box, rt::filter_kind::tent, rt::filter_kind::gaussian,
                                           rt::filter_kind::mitchell};
        rt::image sheet(5 * panel + 4 * gap, 3 * panel + 2 * gap, rt::color(1.0f));
        for (int k = 0; k < 5; ++k)
            rt::paste(sheet, zone_plate(panel, samplers[k], spp, rt::filter_kind::box), k * (panel + gap), 0);
        for (int k = 0; k < 4; ++k)
            rt::paste(sheet, zone_plate(panel, rt::sampler_kind::jittered, spp, filters[k]), k * (panel + gap),
                      panel + gap);
        for (int k = 0; k < 5; ++k)
            rt::paste(sheet, slanted_edge(16, 8, samplers[k], spp), k * (panel + gap), 2 * (panel + gap));
        // the picture is grey: stored as a one-channel PNG (a third of the bytes),
        // through the same color pipeline as every image (sRGB, 8 bits)
        const std::vector<std::uint8_t> rgb = rt::encode_image(sheet, rt::encoding{});
        std::vector<std::uint8_t> grey;
        for (std::size_t k = 0; k < rgb.size(); k += 3)
            grey.push_back(rgb[k]);
        std::vector<std::uint8_t> png;
        auto append = [](void* context, void* data, int size) {
            auto* target = static_cast<std::vector<std::uint8_t>*>(context);
            const auto* first = static_cast<const std::uint8_t*>(data);
            target->insert(target->end(), first, first + size);
        };
        if (!stbi_write_png_to_func(append, &png, sheet.width, sheet.height, 1, grey.data(), sheet.width))
            throw rt::error("PNG encoding failed");
        rt::write_atomically(output, [&](std::ostream& out) {
            out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
        });
        std::cerr << "wrote " << argv[1] << '\n';
        return 0;
    });
}
