# `cmake --install build --prefix P` (docs/library.md): the C++ package.
#   P/lib/libvoxr.so*, P/lib/libvoxr_render.so*      the public API's shared libraries (internals inside)
#   P/include/voxr/*.h                                 the public headers only
#   P/bin/voxr, P/bin/voxr-render (+ the OpenVDB plugin beside them, found there by voxr)
#   P/lib/cmake/voxr/voxr{Config,ConfigVersion,Targets}.cmake: find_package(voxr 0.1) -> voxr::voxr, voxr::render
# Components: runtime (libraries and executables) and devel (headers, SONAME-less links, CMake files); the
# Python wheel installs its own component (python) and takes none of these.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(VOXR_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/voxr)
# Installed programs and libraries find each other relative to themselves, wherever the prefix is moved.
file(RELATIVE_PATH _voxr_bin_to_lib ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}
     ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR})
set_target_properties(voxr voxr-render PROPERTIES INSTALL_RPATH "$ORIGIN/${_voxr_bin_to_lib}")
set(_voxr_api_targets voxr_api)
if(TARGET voxr_render_api)
  list(APPEND _voxr_api_targets voxr_render_api)
endif()
set_target_properties(${_voxr_api_targets} PROPERTIES INSTALL_RPATH "$ORIGIN")
# The public headers take std::span: a consumer compiles as C++20 at least.
target_compile_features(voxr_api INTERFACE cxx_std_20)

install(TARGETS ${_voxr_api_targets} EXPORT voxrTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT devel
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS voxr voxr-render RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
if(TARGET voxr_openvdb_peer)
  install(TARGETS voxr_openvdb_peer LIBRARY DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
endif()
# The public API's headers and nothing else (host/ holds the internals, which stay private).
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/voxr DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT devel
        FILES_MATCHING PATTERN "*.h")

install(EXPORT voxrTargets NAMESPACE voxr:: DESTINATION ${VOXR_INSTALL_CMAKEDIR} COMPONENT devel)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/voxrConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cmake/voxrConfig.cmake INSTALL_DESTINATION ${VOXR_INSTALL_CMAKEDIR})
# 0.x: a new minor version may change the API (docs/library.md), so only the same minor is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/voxrConfigVersion.cmake VERSION ${PROJECT_VERSION}
                                  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/voxrConfig.cmake ${CMAKE_BINARY_DIR}/cmake/voxrConfigVersion.cmake
        DESTINATION ${VOXR_INSTALL_CMAKEDIR} COMPONENT devel)
