# Finds rt's dependencies on the system. Nothing is downloaded.
# When one is missing, configure stops with one message that names the package
# for apt, Homebrew and vcpkg.
include(GNUInstallDirs)

function(rt_require package target apt brew vcpkg)
  if(NOT TARGET ${target})
    message(FATAL_ERROR
      "rt needs ${package} (CMake target ${target}) and it was not found. Install it: "
      "Debian/Ubuntu: sudo apt-get install ${apt}; Homebrew: brew install ${brew}; "
      "vcpkg: vcpkg install ${vcpkg}; or point CMAKE_PREFIX_PATH at it.")
  endif()
endfunction()

include(RtHostHeaders) # cross builds and libc++ (RT_HOST_HEADERS, RT_TINYOBJLOADER_FROM_HEADER)

if(NOT TARGET glm::glm)
  find_package(glm CONFIG QUIET)
endif()
rt_require(GLM glm::glm libglm-dev glm glm)

# Debian's tinyobjloader reports its version as "2rc10": ask for no version.
if(NOT TARGET tinyobjloader::tinyobjloader)
  find_package(tinyobjloader CONFIG QUIET)
endif()
rt_require(tinyobjloader tinyobjloader::tinyobjloader libtinyobjloader-dev tinyobjloader tinyobjloader)

set(THREADS_PREFER_PTHREAD_FLAG ON)
find_package(Threads REQUIRED)

if(RT_BUILD_TESTS)
  if(NOT TARGET doctest::doctest)
    find_package(doctest CONFIG QUIET)
  endif()
  rt_require(doctest doctest::doctest doctest-dev doctest doctest)
endif()

# --- decimal numbers: fast_float or std::from_chars (include/rt/core/decimal_text.hpp)
# rt reads every number of its files and options with fast_float where it is
# found, otherwise with std::from_chars for double, which libc++ before 20
# (macOS) lacks: there fast_float is required. The header decides with
# __has_include, so rt::rt links FastFloat::fast_float whenever it is found:
# Homebrew's and vcpkg's include directories are not on the compiler's
# default path, and every translation unit must see the same parser.
# rt_links_fast_float tells rtConfig.cmake to find it for installed consumers.
find_package(FastFloat CONFIG QUIET)

function(rt_check_from_chars_double)
  include(CheckCXXSourceCompiles)
  # the check compiles as rt's consumers do: C++17 (CMP0067 passes these on)
  set(CMAKE_CXX_STANDARD 17)
  set(CMAKE_CXX_STANDARD_REQUIRED ON)
  set(CMAKE_REQUIRED_QUIET ON)
  check_cxx_source_compiles([[
#include <charconv>
#include <system_error>
#if !(defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L)
#error "no std::from_chars for double"
#endif
int main()
{
    const char text[] = "0.5";
    double value = 0;
    return std::from_chars(text, text + 3, value).ec == std::errc() ? 0 : 1;
}
]] RT_HAVE_FROM_CHARS_DOUBLE)
endfunction()
rt_check_from_chars_double()

if(TARGET FastFloat::fast_float)
  set(rt_links_fast_float ON) # CMakeLists.txt links it to rt::rt
elseif(RT_HAVE_FROM_CHARS_DOUBLE)
  set(rt_links_fast_float OFF)
else()
  message(FATAL_ERROR
    "rt needs fast_float (CMake target FastFloat::fast_float) where the standard library has no "
    "std::from_chars for double (libc++ before 20, as on macOS), and it was not found. Install it: "
    "Debian/Ubuntu: sudo apt-get install libfast-float-dev; Homebrew: brew install fast_float; "
    "vcpkg: vcpkg install fast-float; or point CMAKE_PREFIX_PATH at it.")
endif()
# --- end of decimal numbers
