// app_draw.hpp - what the viewer draws: the image, the inspector's rays over it, and a
// screenshot of the window.
#pragma once

#include "app.hpp"

namespace viewer {

/// The inspected pixel's rays over the image, through the view's camera.
inline void app::draw_overlay()
{
    if (!inspecting_ || !story_)
        return;
    const rt::ray_generator gen = rt::make_ray_generator(view_.cam, view_.width, view_.height);
    const double w = double(view_.width), h = double(view_.height);
    for (const viewer::overlay_segment& seg : viewer::story_segments(*story_, gen, reach_)) {
        const auto seen = viewer::clip(seg.a, seg.b, -1, -1, w + 1, h + 1);
        const std::array<std::uint8_t, 3> rgb = overlay_color(seg.what);
        SDL_SetRenderDrawColor(renderer_.get(), rgb[0], rgb[1], rgb[2], 255);
        if (seen)
            SDL_RenderDrawLineF(renderer_.get(), float(seen->first.x), float(seen->first.y),
                                float(seen->second.x), float(seen->second.y));
        if (seg.ends_at_hit && seg.b.x >= 0 && seg.b.y >= 0 && seg.b.x < w && seg.b.y < h) {
            const SDL_FRect dot{float(seg.b.x) - 2, float(seg.b.y) - 2, 5, 5};
            SDL_RenderFillRectF(renderer_.get(), &dot);
        }
    }
    SDL_SetRenderDrawColor(renderer_.get(), 0, 0, 0, 255);
}

inline void app::draw()
{
    SDL_RenderClear(renderer_.get());
    SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
    draw_overlay();
    SDL_RenderPresent(renderer_.get());
    redraw_ = false;
}

/// What the window shows, read back from the renderer, to a .png or .ppm file.
inline void app::screenshot(const std::string& path)
{
    SDL_RenderClear(renderer_.get());
    SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
    draw_overlay(); // what the window shows
    std::vector<std::uint8_t> pixels(std::size_t(view_.width) * std::size_t(view_.height) * 3);
    if (SDL_RenderReadPixels(renderer_.get(), nullptr, SDL_PIXELFORMAT_RGB24, pixels.data(), view_.width * 3) != 0)
        throw sdl_failure("read the window's pixels back");
    SDL_RenderPresent(renderer_.get());
    const std::string format = rt::image_format_of(stage::file_argument(path));
    if (format == ".pfm")
        throw rt::error(rt::source_location{path}, "expected a screenshot named .png or .ppm, found .pfm; "
                                                   "the window holds bytes, not floats");
    rt::write_atomically(stage::file_argument(path), [&](std::ostream& out) {
        if (format == ".ppm") {
            out << "P6\n" << view_.width << ' ' << view_.height << "\n255\n";
            out.write(reinterpret_cast<const char*>(pixels.data()), std::streamsize(pixels.size()));
        } else {
            const std::vector<std::uint8_t> png = rt::encode_png(view_.width, view_.height, pixels);
            out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
        }
    });
}

} // namespace viewer
