# cmake --install: everything a user needs, standing alone once the source tree and the build folder are gone
# (README.md, "Use it from your own project"; tests/install_package_test.sh checks it):
#   bin/rtdr                       the command line
#   lib/, include/rtdr/            the libraries and their headers (included as in the source tree,
#                                  "filters/svgf/atrous.h"), and lib/cmake/rtdr/, the CMake package
#   share/rtdr/scenes/             the shipped scenes, found there by the installed rtdr and libraries
#   share/rtdr/shaders/            the Vulkan ports' SPIR-V, compiled at build time
#   share/rtdr/eval/               the chart scripts rtdr eval runs (charts.py, chart_layout.py, strip.py)
#   share/doc/rtdr/                the layer contract (buffers.md: every layer name and its conventions) and the
#                                  example project examples/shader_port_check
# Where an installed program finds share/rtdr: core/data_path.h.
#
# find_package(rtdr CONFIG) gives the imported targets rtdr::core, rtdr::filters and rtdr::metrics (component
# filters: no OpenEXR, no Embree, no Vulkan) and rtdr::io, rtdr::scenes, rtdr::raster, rtdr::motion, rtdr::trace
# and rtdr::eval (component render). cmake/rtdrConfig.cmake.in finds their dependencies. The Vulkan ports (gpu/)
# and the command line's own code (app/) are linked into bin/rtdr; they are not installed as libraries.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(RTDR_FILTERS_LIBRARIES rtdr_core rtdr_filters rtdr_metrics)
set(RTDR_RENDER_LIBRARIES rtdr_io rtdr_scenes rtdr_raster rtdr_motion rtdr_trace rtdr_eval)
foreach(library ${RTDR_FILTERS_LIBRARIES} ${RTDR_RENDER_LIBRARIES})
  string(REPLACE "rtdr_" "" export_name ${library})
  # SOVERSION: the ABI's major version, for a build with shared libraries; the shipped build is static.
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${export_name} VERSION ${PROJECT_VERSION}
                                              SOVERSION ${PROJECT_VERSION_MAJOR})
endforeach()
install(TARGETS ${RTDR_FILTERS_LIBRARIES} EXPORT rtdrFiltersTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS ${RTDR_RENDER_LIBRARIES} EXPORT rtdrRenderTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(folder core filters eval scenes raster motion trace)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rtdr
          FILES_MATCHING PATTERN "*.h")
endforeach()

set(RTDR_DATA_DESTINATION ${CMAKE_INSTALL_DATADIR}/rtdr)
install(TARGETS rtdr RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${RTDR_DATA_DESTINATION}/scenes
        FILES_MATCHING PATTERN "*.gltf" PATTERN "*.glb" PATTERN "*.bin" PATTERN "*.png" PATTERN "*.jpg")
install(DIRECTORY ${RTDR_SHADER_DIR}/ DESTINATION ${RTDR_DATA_DESTINATION}/shaders FILES_MATCHING PATTERN "*.spv")
install(FILES ${PROJECT_SOURCE_DIR}/eval/charts.py ${PROJECT_SOURCE_DIR}/eval/chart_layout.py
              ${PROJECT_SOURCE_DIR}/eval/strip.py DESTINATION ${RTDR_DATA_DESTINATION}/eval)
if(RTDR_VIEW)  # rtdr view's page (app/view_server.cpp finds it through core/data_path.h)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/app/view/ DESTINATION ${RTDR_DATA_DESTINATION}/view)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/docs/buffers.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/shader_port_check DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples)

set(RTDR_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/rtdr)
install(EXPORT rtdrFiltersTargets NAMESPACE rtdr:: DESTINATION ${RTDR_CMAKE_DIR})
install(EXPORT rtdrRenderTargets NAMESPACE rtdr:: DESTINATION ${RTDR_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/rtdrConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/rtdrConfig.cmake INSTALL_DESTINATION ${RTDR_CMAKE_DIR}
                              PATH_VARS RTDR_DATA_DESTINATION CMAKE_INSTALL_BINDIR)
# 0.x: every minor version may change the API; from 1.0 on, the same major version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rtdrConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rtdrConfig.cmake ${PROJECT_BINARY_DIR}/rtdrConfigVersion.cmake
        DESTINATION ${RTDR_CMAKE_DIR})
