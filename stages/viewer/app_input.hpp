// app_input.hpp - the viewer's input: SDL events, the keys (the table of viewer_command.hpp), and
// the mouse (click, drag: orbit, pan, zoom).
#pragma once

#include "app.hpp"

namespace viewer {

inline void app::handle(const SDL_Event& event)
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

inline void app::key(SDL_Keycode sym)
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

/// A left click at window pixel (x, y) that does not move, as SDL events.
inline void app::click(int x, int y)
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
inline void app::drag(std::uint8_t button, int dx, int dy)
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

} // namespace viewer
