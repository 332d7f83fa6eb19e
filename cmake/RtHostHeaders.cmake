# Dependencies for builds that cannot use the system's CMake packages as they are.
#
# RT_HOST_HEADERS (set by the cross toolchains in cmake/toolchains/): GLM,
# doctest and tinyobjloader are taken from the build machine's headers
# (RT_HOST_INCLUDE_DIR, /usr/include on Debian). A cross compiler must not see
# that whole folder (the build machine's C library headers would win over its
# own), so each dependency is linked into a folder of its own in the build tree.
#
# RT_TINYOBJLOADER_FROM_HEADER: tinyobjloader's implementation is compiled from
# its header into this build, where the system's library cannot be linked:
# Debian's is built against libstdc++ (so not for clang++ -stdlib=libc++, the
# libcxx preset) and for the build machine (not for a cross build). Such a
# build links a library of its own, so it installs no package (RT_INSTALL).
option(RT_HOST_HEADERS "Take GLM, doctest and tinyobjloader from the build machine's headers (cross builds)" OFF)
option(RT_TINYOBJLOADER_FROM_HEADER "Compile tinyobjloader from its header instead of linking the system's library"
       ${RT_HOST_HEADERS})
set(RT_HOST_INCLUDE_DIR "/usr/include" CACHE PATH "Where RT_HOST_HEADERS finds glm/, doctest/ and tiny_obj_loader.h")

if(RT_HOST_HEADERS)
  set(rt_host_headers "${PROJECT_BINARY_DIR}/host_headers")
  file(MAKE_DIRECTORY "${rt_host_headers}")
  foreach(entry IN ITEMS glm doctest tiny_obj_loader.h)
    if(NOT EXISTS "${RT_HOST_INCLUDE_DIR}/${entry}")
      message(FATAL_ERROR "RT_HOST_HEADERS: expected ${RT_HOST_INCLUDE_DIR}/${entry}, found nothing; install "
                          "libglm-dev doctest-dev libtinyobjloader-dev, or set RT_HOST_INCLUDE_DIR")
    endif()
    file(CREATE_LINK "${RT_HOST_INCLUDE_DIR}/${entry}" "${rt_host_headers}/${entry}" SYMBOLIC)
  endforeach()
  add_library(glm::glm INTERFACE IMPORTED)
  target_include_directories(glm::glm SYSTEM INTERFACE "${rt_host_headers}")
  if(RT_BUILD_TESTS)
    add_library(doctest::doctest INTERFACE IMPORTED)
    target_include_directories(doctest::doctest SYSTEM INTERFACE "${rt_host_headers}")
    # doctest_discover_tests (include(doctest) in tests/) comes with doctest's package
    find_path(rt_doctest_module doctest.cmake PATHS /usr/lib/cmake/doctest /usr/share/doctest/cmake
              NO_CMAKE_FIND_ROOT_PATH NO_DEFAULT_PATH)
    if(NOT rt_doctest_module)
      message(FATAL_ERROR "RT_HOST_HEADERS: expected doctest's CMake module doctest.cmake in /usr/lib/cmake/doctest, "
                          "found none; install doctest-dev")
    endif()
    list(APPEND CMAKE_MODULE_PATH "${rt_doctest_module}")
  endif()
endif()

if(RT_TINYOBJLOADER_FROM_HEADER)
  if(RT_HOST_HEADERS)
    set(rt_tinyobjloader_include "${rt_host_headers}")
  else()
    # the folder of tiny_obj_loader.h: a package's, or the one file of tinyobjloader's
    # release put in a folder by hand (where no package has it)
    find_path(RT_TINYOBJLOADER_INCLUDE_DIR tiny_obj_loader.h DOC "The folder that holds tiny_obj_loader.h")
    if(NOT RT_TINYOBJLOADER_INCLUDE_DIR)
      message(FATAL_ERROR "RT_TINYOBJLOADER_FROM_HEADER: expected tiny_obj_loader.h, found none; install "
                          "libtinyobjloader-dev (Debian/Ubuntu) or tinyobjloader (vcpkg), or put the header "
                          "in a folder and pass -DRT_TINYOBJLOADER_INCLUDE_DIR=<that folder>")
    endif()
    set(rt_tinyobjloader_include "${RT_TINYOBJLOADER_INCLUDE_DIR}")
  endif()
  file(CONFIGURE OUTPUT "${PROJECT_BINARY_DIR}/tinyobjloader_impl.cpp"
       CONTENT "// tinyobjloader's implementation, from its header (cmake/RtHostHeaders.cmake)\n#define TINYOBJLOADER_IMPLEMENTATION\n#include <tiny_obj_loader.h>\n")
  # Not our code: built without rt's warning flags.
  add_library(rt_tinyobjloader STATIC "${PROJECT_BINARY_DIR}/tinyobjloader_impl.cpp")
  target_include_directories(rt_tinyobjloader SYSTEM PUBLIC "${rt_tinyobjloader_include}")
  set_target_properties(rt_tinyobjloader PROPERTIES POSITION_INDEPENDENT_CODE ON)
  add_library(tinyobjloader::tinyobjloader ALIAS rt_tinyobjloader)
endif()
