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
