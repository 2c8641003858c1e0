# libvoxr_render (voxr::render, include/voxr/render.h): the renderer as a shared library, internals linked in
# statically and hidden like libvoxr's (only the API's symbols are exported; docs/library.md). It links
# voxr::voxr publicly for voxr::Error and the shared API.
add_library(voxr_render_api SHARED ${CMAKE_SOURCE_DIR}/host/api/render_api.cpp)
set_target_properties(voxr_render_api PROPERTIES OUTPUT_NAME voxr_render EXPORT_NAME render
                                                 CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
                                                 VERSION ${PROJECT_VERSION} SOVERSION 0)
target_compile_definitions(voxr_render_api PRIVATE VOXR_BUILDING_API)
target_include_directories(voxr_render_api PUBLIC $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/include>
                                                  $<INSTALL_INTERFACE:include>)
# CLI11 (header only): the flags' ranges (cli/option_groups.h) the API checks as the CLI does.
target_link_libraries(voxr_render_api PUBLIC voxr_api
                                      PRIVATE voxr_eval voxr_ref voxr_render voxr_image voxr_io voxr_core CLI11::CLI11)
# cmake/voxr_api.map: only namespace voxr is exported (the std:: template instances render_api.cpp makes too
# would be otherwise).
target_link_options(voxr_render_api PRIVATE -Wl,--exclude-libs,ALL
                    -Wl,--version-script=${CMAKE_SOURCE_DIR}/cmake/voxr_api.map)
set_property(TARGET voxr_render_api APPEND PROPERTY LINK_DEPENDS ${CMAKE_SOURCE_DIR}/cmake/voxr_api.map)
add_library(voxr::render ALIAS voxr_render_api)

# libvoxr exports namespace voxr only as well (the same version script; the API file's std:: instances would
# be exported otherwise). Here rather than in the top-level CMakeLists: it belongs with the package's checks.
target_link_options(voxr_api PRIVATE -Wl,--version-script=${CMAKE_SOURCE_DIR}/cmake/voxr_api.map)
set_property(TARGET voxr_api APPEND PROPERTY LINK_DEPENDS ${CMAKE_SOURCE_DIR}/cmake/voxr_api.map)
