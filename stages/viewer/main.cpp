// viewer - watch a render form, move the camera, save what you see (SDL2).
//
//     viewer scenes/showcase.scene
//     viewer ../shared/meshes/stanford-bunny.obj --aov rays --spp 16
//
// The viewer holds no rendering logic: the scene, the camera's rays and the
// radiance function come from rt/rendering/render_setup.hpp and the options from
// stages/common/render_arguments.hpp, exactly as in stage08_output; the
// progressive loop (progressive.hpp) calls rt::render on crops, and the window
// shows the float image through rt::encode_color (encoding.hpp). So every
// finished level on screen is the image stage08_output writes for the same
// camera and settings, and the save key prints that command.
// Controls, options and the test: docs/viewer.md.
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

#include <rt/system/atomic_file.hpp>
#include <rt/camera/camera.hpp>
#include <rt/output/encoded_output.hpp>
#include <rt/output/encoding.hpp>
#include <rt/core/error.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/core/image.hpp>
#include <rt/output/image_io.hpp>
#include <rt/rendering/progress.hpp>
#include <rt/rendering/render_setup.hpp>
#include <rt/rendering/sampler.hpp>
#include <rt/scene/scene.hpp>
#include <rt/output/tonemap.hpp>

#include "inspector.hpp"
#include "pixel_story.hpp"
#include "support_frame.hpp"

// Under AddressSanitizer the viewer runs LeakSanitizer's check itself, just
// before SDL_Quit (see sdl_session).
#if defined(__SANITIZE_ADDRESS__)
#define RT_VIEWER_LEAK_CHECK 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RT_VIEWER_LEAK_CHECK 1
#endif
#endif
#ifdef RT_VIEWER_LEAK_CHECK
#include <sanitizer/lsan_interface.h>

// A block libdbus loses by itself, which SDL's D-Bus use (screensaver, input
// methods) triggers in every SDL program; read by LeakSanitizer at start.
extern "C" const char* __lsan_default_suppressions() // NOLINT: the name is LeakSanitizer's
{
    return "leak:libdbus-1.so\n";
}
#endif

#include "camera_control.hpp"
#include "progressive.hpp"
#include "render_arguments.hpp"
#include "script.hpp"
#include "stage_main.hpp"

namespace {

const char* controls =
    "Mouse: left drag orbits around the look-at point, right (or middle, or shift + left)\n"
    "drag pans, the wheel zooms.\n"
    "Keys:  1 shaded  2 normals  3 depth  4 position  5 ray directions  6 path traced (stage 11)\n"
    "       m next sampler (auto, center, grid, random, jittered, halton)\n"
    "       f next filter (box, tent, gaussian, mitchell)\n"
    "       ] [ samples per pixel x2 / /2      . , max depth +1 / -1\n"
    "       = - exposure +/- 1/2 stop          t next tone map\n"
    "       r reset the camera   s save the image (and print its stage08_output command)\n"
    "       p print that command   h this help   q or Escape quit\n"
    "       i ray inspector: click a pixel to see its rays (camera white, shadow yellow or red\n"
    "         when blocked, reflection cyan, refraction magenta) and read its story on stderr\n";

const std::string usage = std::string("usage: viewer (SCENE | MODEL.obj) [options]\n"
                                      "Renders a scene file or a bare OBJ model in a window, a coarse preview first,\n"
                                      "then the full image at 1, 4, 16 ... samples per pixel, and restarts whenever\n"
                                      "the camera or a setting changes. The options are stage08_output's:\n") +
                          stage::render_options_usage +
                          "  -o OUTPUT             where the save key writes (.png, .ppm or .pfm; default render.png)\n"
                          "  --script TEXT|@FILE   scripted input (docs/viewer.md): orbit, pan, zoom, key, click,\n"
                          "                        wait, sleep, screenshot, title, save, args, story, quit\n"
                          "  --timeout SECONDS     give up (exit 1) after this long (default: never)\n"
                          "  --help                this text\n\n" +
                          controls;

struct settings {
    stage::render_settings render;
    std::string output = "render.png";
    std::string script;
    std::string script_name = "--script";
    double timeout = 0;
};

/// The settings of the command line; nullopt for --help (the usage is printed).
std::optional<settings> read_arguments(stage::arguments& args)
{
    settings s;
    const std::optional<std::string> input = stage::read_command_line(
        args, usage, "-o, the render options, --script, --timeout",
        [&](const std::string& arg) {
            if (arg == "-o") {
                s.output = args.value_of(arg);
            } else if (stage::read_render_option(args, arg, s.render)) {
                // shared with stage08_output
            } else if (arg == "--script") {
                s.script = args.value_of(arg);
                if (!s.script.empty() && s.script[0] == '@') {
                    s.script_name = s.script.substr(1);
                    std::ifstream in(stage::file_argument(s.script_name), std::ios::binary);
                    if (!in)
                        throw rt::error(rt::source_location{s.script_name},
                                        "expected a readable script file, found none; check the path after '@'");
                    s.script.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
                }
            } else if (arg == "--timeout") {
                s.timeout = stage::parse_number(arg, args.value_of(arg), 0, 86400, true);
            } else {
                return false;
            }
            return true;
        },
        "a scene or OBJ file");
    if (!input)
        return std::nullopt;
    s.render.input = *input;
    return s;
}

/// `text` as one shell word: unchanged when it is plain, else in single quotes.
std::string shell_word(const std::string& text)
{
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string("_./-=+:,@%").find(c) != std::string::npos;
    });
    if (plain)
        return text;
    std::string quoted = "'";
    for (char c : text)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

/// The stage08_output arguments (without -o) that write `done` with `enc`.
std::vector<std::string> stage08_arguments(const std::string& input, const viewer::completed_image& done,
                                           const rt::encoding& enc)
{
    const viewer::view& v = done.settings;
    if (v.path_traced)
        return {}; // command_line says why there is none
    auto number = [](double value) { return rt::exact_number_text(rt::real(value)); };
    std::vector<std::string> a = {input,
                                  "--width", std::to_string(v.width),
                                  "--height", std::to_string(v.height),
                                  "--camera", rt::camera_statement(v.cam),
                                  "--spp", std::to_string(done.pass.samples_per_pixel),
                                  "--sampler", rt::name_of(done.pass.sampler),
                                  "--filter", rt::name_of(v.reconstruction.kind),
                                  "--filter-radius", rt::exact_number_text(v.reconstruction.radius),
                                  "--max-depth", std::to_string(v.max_depth),
                                  "--seed", std::to_string(v.seed)};
    if (v.aov != rt::aov_kind::shaded) {
        a.insert(a.end(), {"--aov", rt::name_of(v.aov)});
    } else {
        a.insert(a.end(), {"--tonemap", rt::name_of(enc.tonemap), "--exposure", number(double(enc.exposure))});
        if (enc.transfer == rt::transfer_kind::gamma)
            a.insert(a.end(), {"--gamma", number(double(enc.gamma))});
    }
    return a;
}

std::string command_line(const std::vector<std::string>& arguments, const std::string& output)
{
    if (arguments.empty()) // a path-traced view: no program takes its camera and options
        return "(none: stage11_path_tracing renders a scene's own camera; the viewer's path-traced view has no "
               "command line)";
    std::string line = "stage08_output";
    for (const std::string& word : arguments)
        line += ' ' + shell_word(word);
    return line + " -o " + shell_word(output);
}

template <class Kind>
Kind next_of(Kind current, const std::vector<Kind>& cycle)
{
    const auto at = std::find(cycle.begin(), cycle.end(), current);
    return at == cycle.end() || at + 1 == cycle.end() ? cycle.front() : *(at + 1);
}

/// A window failure: SDL's own message after ours.
rt::error sdl_failure(const std::string& what)
{
    return rt::error("cannot " + what + ": " + SDL_GetError() +
                     " (is there a display? for a headless run use xvfb-run)");
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

    void handle(const SDL_Event& event)
    {
        switch (event.type) {
        case SDL_QUIT: running_ = false; break;
        case SDL_WINDOWEVENT:
            if (event.window.event == SDL_WINDOWEVENT_EXPOSED)
                redraw_ = true;
            break;
        case SDL_MOUSEBUTTONDOWN:
            if (event.button.button == SDL_BUTTON_LEFT) {
                pressed_ = true;
                dragged_ = false;
            }
            break;
        case SDL_MOUSEBUTTONUP:
            // a left click that did not move: the inspector's pick
            if (event.button.button == SDL_BUTTON_LEFT && pressed_ && !dragged_ && inspecting_)
                inspect(event.button.x, event.button.y);
            pressed_ = false;
            break;
        case SDL_MOUSEMOTION: {
            const std::uint32_t buttons = event.motion.state;
            if (buttons & SDL_BUTTON_LMASK)
                dragged_ = true;
            const bool shift = (SDL_GetModState() & KMOD_SHIFT) != 0;
            const rt::real dx = rt::real(event.motion.xrel), dy = rt::real(event.motion.yrel);
            if ((buttons & SDL_BUTTON_LMASK) && !shift) {
                view_.cam = viewer::orbit(view_.cam, dx, dy);
                restart();
            } else if (buttons & (SDL_BUTTON_LMASK | SDL_BUTTON_RMASK | SDL_BUTTON_MMASK)) {
                view_.cam = viewer::pan(view_.cam, dx, dy, view_.width, view_.height);
                restart();
            }
            break;
        }
        case SDL_MOUSEWHEEL: {
            const int sign = event.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -1 : 1;
            view_.cam = viewer::zoom(view_.cam, rt::real(sign * event.wheel.y), view_.width, view_.height);
            restart();
            break;
        }
        case SDL_KEYDOWN: key(event.key.keysym.sym); break;
        default: break;
        }
    }

    void key(SDL_Keycode sym)
    {
        switch (sym) {
        case SDLK_1: set_aov(rt::aov_kind::shaded); break;
        case SDLK_2: set_aov(rt::aov_kind::normal); break;
        case SDLK_3: set_aov(rt::aov_kind::depth); break;
        case SDLK_4: set_aov(rt::aov_kind::position); break;
        case SDLK_5: set_aov(rt::aov_kind::rays); break;
        case SDLK_6:
            view_.aov = rt::aov_kind::shaded;
            view_.path_traced = true;
            say("view: path traced (stage 11: MIS, Russian roulette; the glowing triangles and the background light it)");
            restart();
            break;
        case SDLK_m: {
            // auto (stage08_output's default for each level), then each sampler
            const std::vector<rt::sampler_kind> kinds = {rt::sampler_kind::center, rt::sampler_kind::grid,
                                                         rt::sampler_kind::random, rt::sampler_kind::jittered,
                                                         rt::sampler_kind::halton};
            if (!view_.sampler)
                view_.sampler = kinds.front();
            else if (*view_.sampler == kinds.back())
                view_.sampler.reset();
            else
                view_.sampler = next_of(*view_.sampler, kinds);
            say(std::string("sampler: ") + (view_.sampler ? rt::name_of(*view_.sampler) : "auto"));
            restart();
            break;
        }
        case SDLK_f:
            view_.reconstruction = rt::make_filter(next_of(view_.reconstruction.kind,
                                                           {rt::filter_kind::box, rt::filter_kind::tent,
                                                            rt::filter_kind::gaussian, rt::filter_kind::mitchell}));
            say(std::string("filter: ") + rt::name_of(view_.reconstruction.kind));
            restart();
            break;
        case SDLK_RIGHTBRACKET:
            view_.samples_per_pixel = std::min(view_.samples_per_pixel * 2, 1 << 16);
            restart();
            break;
        case SDLK_LEFTBRACKET:
            view_.samples_per_pixel = std::max(view_.samples_per_pixel / 2, 1);
            restart();
            break;
        case SDLK_PERIOD:
            view_.max_depth = std::min(view_.max_depth + 1, 64);
            say("max depth: " + std::to_string(view_.max_depth));
            restart();
            break;
        case SDLK_COMMA:
            view_.max_depth = std::max(view_.max_depth - 1, 0);
            say("max depth: " + std::to_string(view_.max_depth));
            restart();
            break;
        case SDLK_EQUALS:
        case SDLK_PLUS:
        case SDLK_KP_PLUS:
            encoding_.exposure = std::min(encoding_.exposure + 0.5f, 64.0f);
            reencode();
            break;
        case SDLK_MINUS:
        case SDLK_KP_MINUS:
            encoding_.exposure = std::max(encoding_.exposure - 0.5f, -64.0f);
            reencode();
            break;
        case SDLK_t:
            encoding_.tonemap =
                next_of(encoding_.tonemap,
                        {rt::tonemap_kind::clamp, rt::tonemap_kind::reinhard, rt::tonemap_kind::aces});
            say(std::string("tone map: ") + rt::name_of(encoding_.tonemap));
            reencode();
            break;
        case SDLK_r:
        case SDLK_HOME:
            view_.cam = initial_;
            restart();
            break;
        case SDLK_s:
            save_to_ = set_.output;
            if (!progressive_->completed())
                say("saving " + set_.output + " when the first full-resolution pass is done");
            break;
        case SDLK_p: {
            const std::optional<viewer::completed_image> done = progressive_->completed();
            if (done)
                std::cerr << command_line(stage08_arguments(set_.render.input, *done, encoding_), set_.output) << '\n';
            else
                say("no full-resolution pass is done yet");
            break;
        }
        case SDLK_i:
            inspecting_ = !inspecting_;
            say(inspecting_ ? "ray inspector on: click a pixel" : "ray inspector off");
            redraw_ = true;
            break;
        case SDLK_h:
        case SDLK_F1: std::cerr << controls; break;
        case SDLK_q:
        case SDLK_ESCAPE: running_ = false; break;
        default: break;
        }
    }

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
    void draw_overlay()
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

    void draw()
    {
        SDL_RenderClear(renderer_.get());
        SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
        draw_overlay();
        SDL_RenderPresent(renderer_.get());
        redraw_ = false;
    }

    /// What the window shows, read back from the renderer, to a .png or .ppm file.
    void screenshot(const std::string& path)
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
    void step_script()
    {
        while (next_command_ < commands_.size()) {
            const viewer::script_command& c = commands_[next_command_];
            if (c.name == "wait") {
                if (!view_is_current())
                    return;
                if (!status_.error.empty())
                    throw rt::error(rt::to_string(c.where) + ": the render failed: " + status_.error);
                const bool enough = c.arguments.empty() ? status_.finished
                                                        : status_.levels_done >= int(c.number(0)) || status_.finished;
                if (!enough)
                    return;
            } else if (c.name == "sleep") {
                const auto now = std::chrono::steady_clock::now();
                if (!sleep_until_) {
                    sleep_until_ = now + std::chrono::milliseconds(static_cast<long long>(c.number(0)));
                    return;
                }
                if (now < *sleep_until_)
                    return;
                sleep_until_.reset();
            } else if (c.name == "orbit" || c.name == "pan") {
                drag(c.name == "orbit" ? SDL_BUTTON_LEFT : SDL_BUTTON_RIGHT, int(c.number(0)), int(c.number(1)));
                ++next_command_;
                return; // the events are handled before the next command
            } else if (c.name == "zoom") {
                SDL_Event e{};
                e.type = SDL_MOUSEWHEEL;
                e.wheel.windowID = SDL_GetWindowID(window_.get());
                e.wheel.y = int(c.number(0));
                e.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
                SDL_PushEvent(&e);
                ++next_command_;
                return;
            } else if (c.name == "click") {
                click(int(c.number(0)), int(c.number(1)));
                ++next_command_;
                return;
            } else if (c.name == "story") {
                if (!story_)
                    throw rt::error(rt::to_string(c.where) + ": expected a pixel's story, found none: press "
                                                             "'key i' and 'click X Y' first");
                rt::write_atomically(stage::file_argument(c.arguments[0]),
                                     [&](std::ostream& out) { stage::print_story_json(out, *story_, story_scene_); });
            } else if (c.name == "key") {
                SDL_Event e{};
                e.type = SDL_KEYDOWN;
                e.key.windowID = SDL_GetWindowID(window_.get());
                e.key.state = SDL_PRESSED;
                e.key.keysym.sym = SDL_GetKeyFromName(c.arguments[0].c_str());
                e.key.keysym.scancode = SDL_GetScancodeFromKey(e.key.keysym.sym);
                SDL_PushEvent(&e);
                e.type = SDL_KEYUP;
                e.key.state = SDL_RELEASED;
                SDL_PushEvent(&e);
                ++next_command_;
                return;
            } else if (c.name == "screenshot") {
                screenshot(c.arguments[0]);
            } else if (c.name == "title") {
                update_title(true);
                const std::string text = SDL_GetWindowTitle(window_.get());
                rt::write_atomically(stage::file_argument(c.arguments[0]),
                                     [&](std::ostream& out) { out << text << '\n'; });
            } else if (c.name == "save" || c.name == "args") {
                const std::optional<viewer::completed_image> done = progressive_->completed();
                if (!view_is_current() || !done)
                    return; // until the first full-resolution level is done
                if (c.name == "save") {
                    save(*done, c.arguments[0], false);
                } else {
                    const std::vector<std::string> words = stage08_arguments(set_.render.input, *done, encoding_);
                    rt::write_atomically(stage::file_argument(c.arguments[0]), [&](std::ostream& out) {
                        for (const std::string& word : words)
                            out << word << '\n';
                    });
                }
            } else if (c.name == "quit") {
                running_ = false;
            }
            ++next_command_;
        }
    }

    /// A left click at window pixel (x, y) that does not move, as SDL events.
    void click(int x, int y)
    {
        SDL_Event e{};
        e.type = SDL_MOUSEBUTTONDOWN;
        e.button.windowID = SDL_GetWindowID(window_.get());
        e.button.button = SDL_BUTTON_LEFT;
        e.button.state = SDL_PRESSED;
        e.button.clicks = 1;
        e.button.x = x;
        e.button.y = y;
        SDL_PushEvent(&e);
        e.type = SDL_MOUSEBUTTONUP;
        e.button.state = SDL_RELEASED;
        SDL_PushEvent(&e);
    }

    /// A drag with `button` from the window's centre by (dx, dy), as SDL events.
    void drag(std::uint8_t button, int dx, int dy)
    {
        const std::uint32_t window = SDL_GetWindowID(window_.get());
        const int x = view_.width / 2, y = view_.height / 2;
        SDL_Event e{};
        e.type = SDL_MOUSEBUTTONDOWN;
        e.button.windowID = window;
        e.button.button = button;
        e.button.state = SDL_PRESSED;
        e.button.x = x;
        e.button.y = y;
        SDL_PushEvent(&e);
        e = SDL_Event{};
        e.type = SDL_MOUSEMOTION;
        e.motion.windowID = window;
        e.motion.state = SDL_BUTTON(button);
        e.motion.x = x + dx;
        e.motion.y = y + dy;
        e.motion.xrel = dx;
        e.motion.yrel = dy;
        SDL_PushEvent(&e);
        e = SDL_Event{};
        e.type = SDL_MOUSEBUTTONUP;
        e.button.windowID = window;
        e.button.button = button;
        e.button.state = SDL_RELEASED;
        e.button.x = x + dx;
        e.button.y = y + dy;
        SDL_PushEvent(&e);
    }

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

/// SDL_Init and SDL_Quit around the window's life.
class sdl_session {
public:
    sdl_session()
    {
        if (SDL_Init(SDL_INIT_VIDEO) != 0)
            throw sdl_failure("start SDL's video");
    }
    sdl_session(const sdl_session&) = delete;
    sdl_session& operator=(const sdl_session&) = delete;
    ~sdl_session()
    {
#ifdef RT_VIEWER_LEAK_CHECK
        // SDL 2 on X11 leaves about 1 KB in 3 blocks to libdbus and to libraries it
        // unloads in SDL_Quit (a five-line SDL program does the same), which the
        // check at exit reports without a culprit. Checked now, after the window
        // and every thread of ours are gone, SDL's blocks are still reachable and
        // any block of ours that is lost is reported (the check at exit is then off).
        __lsan_do_leak_check();
#endif
        SDL_Quit();
    }
};

} // namespace

int main(int argc, char** argv)
{
    return stage::run("viewer", [&] {
        stage::arguments args(argc, argv);
        const std::optional<settings> arguments = read_arguments(args);
        if (!arguments)
            return 0; // --help
        const settings& set = *arguments;
        rt::check_image_output(stage::file_argument(set.output)); // the save key must not fail at the end
        // script errors before the window opens; the files a script writes are outputs too
        std::vector<std::filesystem::path> outputs{stage::file_argument(set.output)};
        for (const viewer::script_command& c : viewer::parse_script(set.script, set.script_name))
            if (c.name == "save" || c.name == "screenshot" || c.name == "title" || c.name == "args" ||
                c.name == "story")
                outputs.push_back(stage::file_argument(c.arguments[0]));
        const bool obj = rt::has_obj_extension(stage::file_argument(set.render.input));
        stage::check_input_and_outputs(set.render.input, obj ? "an OBJ file" : "a scene file", outputs);
        rt::scene scene = stage::load_render_input(set.render);
        // its OBJ and MTL files too
        rt::check_not_input(outputs, rt::files_read(stage::file_argument(set.render.input), scene));
        const sdl_session sdl;
        // without a display SDL falls back to a driver that shows nothing: fine for a script, not for a person
        const std::string driver = SDL_GetCurrentVideoDriver() ? SDL_GetCurrentVideoDriver() : "";
        if ((driver == "offscreen" || driver == "dummy") && set.script.empty())
            throw rt::error("cannot open a window: no display (SDL chose its '" + driver +
                            "' video driver, which shows nothing); set DISPLAY, or run under xvfb-run");
        app window(set, std::move(scene));
        return window.run();
    });
}
