# cmake --install: RTDR as a CMake package, for a user's own project (README.md, "Use it from your own project";
# examples/shader_port_check/). find_package(rtdr CONFIG) gives the imported targets rtdr::core, rtdr::filters
# and rtdr::metrics (component filters: no Embree, no Vulkan), and rtdr::scenes, rtdr::raster, rtdr::motion,
# rtdr::trace and rtdr::eval (component render). cmake/rtdrConfig.cmake.in finds their dependencies.
#
# The public headers are every header of the installed libraries' folders, installed under include/rtdr and
# included as in the source tree ("filters/svgf/atrous.h"). app/ (the command line) and gpu/ (the Vulkan ports)
# are private: not installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(RTDR_FILTERS_LIBRARIES rtdr_core rtdr_filters rtdr_metrics)
set(RTDR_RENDER_LIBRARIES rtdr_scenes rtdr_raster rtdr_motion rtdr_trace rtdr_eval)
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

set(RTDR_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/rtdr)
install(EXPORT rtdrFiltersTargets NAMESPACE rtdr:: DESTINATION ${RTDR_CMAKE_DIR})
install(EXPORT rtdrRenderTargets NAMESPACE rtdr:: DESTINATION ${RTDR_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/rtdrConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/rtdrConfig.cmake INSTALL_DESTINATION ${RTDR_CMAKE_DIR})
# 0.x: every minor version may change the API; from 1.0 on, the same major version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rtdrConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rtdrConfig.cmake ${PROJECT_BINARY_DIR}/rtdrConfigVersion.cmake
        DESTINATION ${RTDR_CMAKE_DIR})
