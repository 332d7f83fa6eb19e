# Toolchain: 64-bit ARM Linux (arm64, as Apple silicon's processors), built on
# an x86-64 Debian machine with Debian's cross compiler (g++-aarch64-linux-gnu)
# and run with qemu's user-mode emulator (qemu-user): CMake runs every test,
# and doctest's test discovery, through CMAKE_CROSSCOMPILING_EMULATOR.
# Used by the arm64-cross preset (CMakePresets.json). qemu gives no timing.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Static programs: qemu then needs no arm64 copy of the C library at run time.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
find_program(RT_QEMU_AARCH64 qemu-aarch64 REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR "${RT_QEMU_AARCH64}")
# Libraries and headers of the target come from the cross sysroot only; the
# header-only dependencies come from the build machine (cmake/RtHostHeaders.cmake).
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(RT_HOST_HEADERS ON CACHE BOOL "GLM, doctest and tinyobjloader from the build machine's headers")
