# Install the headers and an rtConfig.cmake so that another project writes
#   find_package(rt CONFIG REQUIRED)  and links  rt::rt
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS rt EXPORT rtTargets)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/rt" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/compat/rt" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}") # old paths, 0.2 only
install(FILES "${PROJECT_SOURCE_DIR}/third_party/stb/stb_image_write.h"
              "${PROJECT_SOURCE_DIR}/third_party/stb/LICENSE"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/stb")
install(EXPORT rtTargets NAMESPACE rt:: DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/rt")

configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/rtConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/rtConfig.cmake"
  INSTALL_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/rt")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/rtConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES "${PROJECT_BINARY_DIR}/rtConfig.cmake" "${PROJECT_BINARY_DIR}/rtConfigVersion.cmake"
        DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/rt")
