// app.hpp - the viewer's window: the view, the progressive renderer behind it,
// and the loop that handles events, pulls finished levels and draws. Its input
// (app_input.hpp), script (app_script.hpp) and drawing (app_draw.hpp) are
// defined in their own files.
#pragma once

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <SDL.h>

#include <rt/camera/camera.hpp>
#include <rt/core/error.hpp>
#include <rt/core/image.hpp>
#include <rt/output/encoded_output.hpp>
#include <rt/output/encoding.hpp>
#include <rt/output/image_io.hpp>
#include <rt/output/tonemap.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/rendering/progress.hpp>
#include <rt/rendering/render_setup.hpp>
#include <rt/rendering/sampler.hpp>
#include <rt/scene/scene.hpp>
#include <rt/system/atomic_file.hpp>

#include "camera_control.hpp"
#include "command_echo.hpp"
#include "inspector.hpp"
#include "pixel_story.hpp"
#include "progressive.hpp"
#include "render_arguments.hpp"
#include "script.hpp"
#include "sdl_window.hpp"
#include "stage_main.hpp"
#include "support_frame.hpp"
#include "viewer_command.hpp"

namespace viewer {

template <class Kind>
Kind next_of(Kind current, const std::vector<Kind>& cycle)
{
    const auto at = std::find(cycle.begin(), cycle.end(), current);
    return at == cycle.end() || at + 1 == cycle.end() ? cycle.front() : *(at + 1);
}

class app {
public:
    app(const settings& set, rt::scene scene)
        : set_(set), initial_(scene.cam), encoding_(set.render.encoding)
    {
        const rt::render_options options = stage::render_options_for(set.render, scene);
        rt::check_render_options(options);
        view_.cam = scene.cam;
        view_.width = options.width;
        view_.height = options.height;
        view_.aov = set.render.aov;
        view_.sampler = set.render.sampler;
        view_.samples_per_pixel = options.samples_per_pixel;
        view_.max_depth = scene.max_depth;
        view_.reconstruction = options.reconstruction;
        view_.seed = options.seed;
        view_.threads = options.threads;
        commands_ = viewer::parse_script(set.script, set.script_name);
        for (const viewer::script_command& c : commands_)
            if (c.name == "key" && SDL_GetKeyFromName(c.arguments[0].c_str()) == SDLK_UNKNOWN)
                throw rt::make_error(c.where, "an SDL key name (\"5\", \"]\", \"s\", \"Escape\")",
                                     stage::quoted(c.arguments[0]));

        window_.reset(SDL_CreateWindow("rt viewer", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, view_.width,
                                       view_.height, SDL_WINDOW_SHOWN));
        if (!window_)
            throw sdl_failure("open a window");
        renderer_.reset(SDL_CreateRenderer(window_.get(), -1, 0));
        if (!renderer_)
            throw sdl_failure("create a renderer for the window");
        texture_.reset(SDL_CreateTexture(renderer_.get(), SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING,
                                         view_.width, view_.height));
        if (!texture_)
            throw sdl_failure("create a texture");
        bytes_.assign(std::size_t(view_.width) * std::size_t(view_.height) * 3, 0);
        SDL_UpdateTexture(texture_.get(), nullptr, bytes_.data(), view_.width * 3);
        // the inspector's copy: the worker thread alone reads the progressive renderer's
        const rt::aabb box = rt::scene_bounds(scene);
        reach_ = box.empty() ? 100.0 : 2 * double(glm::length(box.hi - box.lo));
        scene_ = scene;
        progressive_.emplace(std::move(scene));
        progressive_->start(view_);
    }

    app(const app&) = delete;
    app& operator=(const app&) = delete;

    ~app() { progressive_.reset(); } // stop the worker before the window goes

    /// Runs until the window closes; the exit code.
    int run()
    {
        const auto started = std::chrono::steady_clock::now();
        while (running_) {
            SDL_Event event;
            if (SDL_WaitEventTimeout(&event, 10)) {
                handle(event);
                while (SDL_PollEvent(&event))
                    handle(event);
            }
            if (view_changed_) {
                progressive_->start(view_);
                view_changed_ = false;
            }
            pull();
            update_title();
            if (save_to_) {
                const std::optional<viewer::completed_image> done = progressive_->completed();
                if (done) {
                    save(*done, *save_to_, true);
                    save_to_.reset();
                }
            }
            if (redraw_)
                draw();
            step_script();
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            if (set_.timeout > 0 && elapsed > set_.timeout) {
                std::string where;
                if (next_command_ < commands_.size())
                    where = " at " + rt::to_string(commands_[next_command_].where) + " ('" +
                            commands_[next_command_].name + "')";
                throw rt::error("timed out after " + rt::detail::format_duration(set_.timeout) + where);
            }
        }
        return 0;
    }

private:
    void restart() { view_changed_ = true; }

    void handle(const SDL_Event& event);

    void key(SDL_Keycode sym);

    void set_aov(rt::aov_kind aov)
    {
        view_.aov = aov;
        view_.path_traced = false;
        say(std::string("view: ") + rt::name_of(aov));
        restart();
    }

    static void say(const std::string& message) { std::cerr << "viewer: " << message << '\n'; }

    /// The encoding the displayed image is shown (and saved) with.
    /// (For the depth view it depends on the image's farthest hit, so a new row may change every row.)
    rt::encoding display_encoding() const { return rt::output_encoding(status_.aov, encoding_, shown_); }

    void reencode()
    {
        if (shown_.height > 0)
            encode_rows(0, shown_.height);
        say("exposure " + rt::exact_number_text(rt::real(encoding_.exposure)) + ", tone map " +
            rt::name_of(encoding_.tonemap));
    }

    /// Bytes and texture of rows [y0, y1) of the shown image, through the color pipeline.
    void encode_rows(int y0, int y1)
    {
        const rt::encoding enc = display_encoding();
        const std::size_t row_bytes = std::size_t(shown_.width) * 3;
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < shown_.width; ++x) {
                const std::array<std::uint8_t, 3> rgb = rt::encode_color(shown_.at(x, y), enc);
                std::copy(rgb.begin(), rgb.end(), &bytes_[std::size_t(y) * row_bytes + std::size_t(x) * 3]);
            }
        const SDL_Rect rows{0, y0, shown_.width, y1 - y0};
        SDL_UpdateTexture(texture_.get(), &rows, &bytes_[std::size_t(y0) * row_bytes], int(row_bytes));
        redraw_ = true;
    }

    /// Takes the worker's new rows and status.
    void pull()
    {
        const rt::aov_kind before = status_.aov;
        const float exposure_before = display_encoding().exposure;
        const std::pair<int, int> rows = progressive_->take(shown_, status_);
        if ((status_.aov != before || display_encoding().exposure != exposure_before) && shown_.height > 0)
            encode_rows(0, shown_.height);
        else if (rows.first < rows.second)
            encode_rows(rows.first, rows.second);
        if (!status_.error.empty() && status_.generation != reported_error_) {
            std::cerr << "viewer: " << status_.error << '\n';
            reported_error_ = status_.generation;
        }
    }

    bool view_is_current() const { return !view_changed_ && status_.generation == progressive_->generation(); }

    void update_title(bool now_or_never = false)
    {
        const auto now = std::chrono::steady_clock::now();
        if (!now_or_never && now - titled_ < std::chrono::milliseconds(200))
            return;
        titled_ = now;
        std::ostringstream title;
        title << "rt viewer - " << (view_.path_traced ? "path traced" : rt::name_of(view_.aov)) << " - ";
        if (!status_.error.empty()) {
            title << "error: " << status_.error;
        } else {
            title << status_.samples_per_pixel << '/'
                  << rt::effective_samples(view_.sampler.value_or(rt::default_sampler(view_.samples_per_pixel)),
                                           view_.samples_per_pixel)
                  << " spp";
            if (status_.finished)
                title << " done";
            else
                title << ' ' << int(status_.level_fraction * 100) << '%';
            title << " - " << rt::detail::format_duration(status_.seconds);
            if (status_.seconds > 0)
                title << " - " << rt::detail::format_count(double(status_.rays) / status_.seconds) << "rays/s";
        }
        SDL_SetWindowTitle(window_.get(), title.str().c_str());
    }

    /// The scene as the view shows it: its camera and max depth.
    rt::scene view_scene() const
    {
        rt::scene s = scene_;
        s.cam = view_.cam;
        s.max_depth = view_.max_depth;
        return s;
    }

    /// The story of the pixel at window point (x, y): exactly what
    /// `stage08_output ARGS --pixel-json x y` prints for the view (its
    /// arguments: the `args` command), printed on stderr and drawn.
    void inspect(int x, int y)
    {
        if (x < 0 || y < 0 || x >= view_.width || y >= view_.height)
            return;
        const rt::scene s = view_scene();
        stage::story st = stage::shaded_story(s, "stage08_output", x, y, view_.width, view_.height);
        const std::optional<viewer::completed_image> done = progressive_->completed();
        stage::add_encoding_story(st, encoding_,
                                  done ? done->pass.samples_per_pixel : view_.samples_per_pixel);
        if (view_.aov != rt::aov_kind::shaded)
            say("the story is the shaded image's (key 1), whatever the view shows");
        stage::print_story(std::cerr, st, s);
        story_ = std::move(st);
        story_scene_ = s;
        redraw_ = true;
    }

    /// The inspected pixel's rays over the image, through the view's camera.
    void draw_overlay();

    static std::array<std::uint8_t, 3> overlay_color(viewer::ray_kind k)
    {
        switch (k) {
        case viewer::ray_kind::camera: return {255, 255, 255};
        case viewer::ray_kind::shadow_visible: return {255, 220, 0};
        case viewer::ray_kind::shadow_blocked: return {220, 40, 0};
        case viewer::ray_kind::reflection: return {0, 220, 255};
        case viewer::ray_kind::refraction: return {255, 0, 200};
        case viewer::ray_kind::other: break;
        }
        return {160, 160, 160};
    }

    void draw();

    /// What the window shows, read back from the renderer, to a .png or .ppm file.
    void screenshot(const std::string& path);

    void save(const viewer::completed_image& done, const std::string& path, bool tell)
    {
        const rt::encoding enc = rt::output_encoding(done.settings.aov, encoding_, done.pixels);
        rt::save_image_encoded(stage::file_argument(path), done.pixels, enc);
        if (tell)
            std::cerr << "viewer: wrote " << path << " (" << done.pass.samples_per_pixel
                      << " spp); the same image: "
                      << command_line(stage08_arguments(set_.render.input, done, encoding_), path) << '\n';
    }

    /// Runs script commands until one has to wait (or pushed events that must be handled first).
    void step_script();

    /// A left click at window pixel (x, y) that does not move, as SDL events.
    void click(int x, int y);

    /// A drag with `button` from the window's centre by (dx, dy), as SDL events.
    void drag(std::uint8_t button, int dx, int dy);

    settings set_;
    rt::camera initial_;
    rt::encoding encoding_;
    viewer::view view_;
    std::vector<viewer::script_command> commands_;
    std::size_t next_command_ = 0;
    std::optional<std::chrono::steady_clock::time_point> sleep_until_;

    struct sdl_deleter {
        void operator()(SDL_Window* w) const { SDL_DestroyWindow(w); }
        void operator()(SDL_Renderer* r) const { SDL_DestroyRenderer(r); }
        void operator()(SDL_Texture* t) const { SDL_DestroyTexture(t); }
    };
    // destroyed in the reverse order: texture, renderer, window
    std::unique_ptr<SDL_Window, sdl_deleter> window_;
    std::unique_ptr<SDL_Renderer, sdl_deleter> renderer_;
    std::unique_ptr<SDL_Texture, sdl_deleter> texture_;
    std::optional<viewer::progressive_renderer> progressive_;

    rt::scene scene_;                     ///< for the inspector's stories
    double reach_ = 100;                  ///< how far a ray that hits nothing is drawn
    bool inspecting_ = false, pressed_ = false, dragged_ = false;
    std::optional<stage::story> story_;   ///< the inspected pixel's
    rt::scene story_scene_;               ///< the scene it was traced in (camera, max depth)

    rt::image shown_;
    viewer::status status_;
    std::vector<std::uint8_t> bytes_;
    std::optional<std::string> save_to_;
    std::uint64_t reported_error_ = 0;
    std::chrono::steady_clock::time_point titled_{};
    bool running_ = true;
    bool view_changed_ = false;
    bool redraw_ = true;
};

} // namespace viewer
