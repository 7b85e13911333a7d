# Installs the libraries, public headers, shared GLSL/C++ headers and an exported CMake package:
# find_package(penumbra) gives penumbra::core, penumbra::shaders and penumbra::gl.
include(CMakePackageConfigHelpers)

set(PENUMBRA_INSTALL_TARGETS penumbra_core penumbra_shaders penumbra_truth)
if(TARGET penumbra_gl)
  list(APPEND PENUMBRA_INSTALL_TARGETS penumbra_gl penumbra_compare penumbra_tune)
endif()
install(TARGETS ${PENUMBRA_INSTALL_TARGETS} penumbra_warnings EXPORT penumbraTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY include/penumbra DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The shared headers are both C++ API (parameter blocks) and GLSL for engines to take.
install(DIRECTORY src/shaders/shared DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/penumbra)
# GLSL for hosts' own shaders (docs/integration.md): penumbra_<technique>.glsl, self-contained,
# and the library files they come from (lib/penumbra_shadow.glsl with shared/) for GLs with
# ARB_shading_language_include.
set(PENUMBRA_GLSL_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/penumbra/glsl)
install(DIRECTORY ${PENUMBRA_GLSL_BUILD_DIR}/ DESTINATION ${PENUMBRA_GLSL_INSTALL_DIR})
install(DIRECTORY src/shaders/lib src/shaders/shared DESTINATION ${PENUMBRA_GLSL_INSTALL_DIR})

set(PENUMBRA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/penumbra)
install(EXPORT penumbraTargets NAMESPACE penumbra:: DESTINATION ${PENUMBRA_CMAKE_DIR})
configure_package_config_file(cmake/penumbraConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfig.cmake INSTALL_DESTINATION ${PENUMBRA_CMAKE_DIR}
  PATH_VARS PENUMBRA_GLSL_INSTALL_DIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/penumbraConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/penumbraConfigVersion.cmake
        DESTINATION ${PENUMBRA_CMAKE_DIR})
