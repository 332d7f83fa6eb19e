// sdl_window.hpp - SDL around the viewer: a failure with SDL's own words, and
// SDL_Init and SDL_Quit around the window's life (with LeakSanitizer's check
// just before SDL_Quit under AddressSanitizer).
#pragma once

#include <string>

#include <SDL.h>

#include <rt/core/error.hpp>

#include "leak_check.hpp"

namespace viewer {

/// A window failure: SDL's own message after ours.
inline rt::error sdl_failure(const std::string& what)
{
    return rt::error("cannot " + what + ": " + SDL_GetError() +
                     " (is there a display? for a headless run use xvfb-run)");
}

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

} // namespace viewer
