# Toolchain: 64-bit Windows, built on a Debian machine with MinGW-w64's g++
# (g++-mingw-w64-x86-64-posix: the POSIX thread model, which std::thread
# needs) and run with Wine (wine64): CMake runs every test, and doctest's test
# discovery, through CMAKE_CROSSCOMPILING_EMULATOR. Used by the windows-cross
# preset (CMakePresets.json). MSVC is not what this checks.
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(CMAKE_C_COMPILER x86_64-w64-mingw32-gcc-posix)
set(CMAKE_CXX_COMPILER x86_64-w64-mingw32-g++-posix)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
# Static programs: Wine then needs no copy of libstdc++, libgcc or winpthread.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
# Debian installs wine64 outside PATH unless the wine package is there too.
find_program(RT_WINE NAMES wine64 wine PATHS /usr/lib/wine NO_CMAKE_FIND_ROOT_PATH REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR "${RT_WINE}")
set(CMAKE_FIND_ROOT_PATH /usr/x86_64-w64-mingw32)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(RT_HOST_HEADERS ON CACHE BOOL "GLM, doctest and tinyobjloader from the build machine's headers")
