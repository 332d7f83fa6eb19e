// leak_check.hpp - under AddressSanitizer, RT_VIEWER_LEAK_CHECK: the viewer runs
// LeakSanitizer's check itself, before SDL_Quit (sdl_window.hpp). Reached, through
// sdl_window.hpp, by the viewer's one translation unit, main.cpp: it defines
// LeakSanitizer's suppressions (a function, so one unit only).
#pragma once

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
