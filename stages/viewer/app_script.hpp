// app_script.hpp - the viewer's --script: each command run in turn, waiting where it
// must (for a finished level, a sleep), as docs/viewer.md describes.
#pragma once

#include "app.hpp"

namespace viewer {

/// Runs script commands until one has to wait (or pushed events that must be handled first).
inline void app::step_script()
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

} // namespace viewer
