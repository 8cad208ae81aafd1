# `cmake --install` puts the effect library where a host's build finds it:
#   lib/libvsgl_gi.a, lib/libvsgl_engine.a       the module and the engine substrate it runs on
#   include/vsgl/gi/*.h                          the public API (docs/integration.md)
#   include/vsgl/shared/*.h                      the std430 layouts the API's buffers follow
#   lib/cmake/vsgl/                              find_package(vsgl) -> vsgl::gi
#   lib/pkgconfig/vsgl.pc                        the same for pkg-config
include(CMakePackageConfigHelpers)

set_target_properties(vsgl_gi PROPERTIES EXPORT_NAME gi)
set_target_properties(vsgl_engine PROPERTIES EXPORT_NAME engine)
install(TARGETS vsgl_gi vsgl_engine EXPORT vsglTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/gi/include/gi DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vsgl)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/shaders/shared DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vsgl
        FILES_MATCHING PATTERN "*.h")

set(VSGL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/vsgl)
install(EXPORT vsglTargets NAMESPACE vsgl:: DESTINATION ${VSGL_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/vsglConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/vsglConfig.cmake INSTALL_DESTINATION ${VSGL_CMAKE_DIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/vsglConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/vsglConfig.cmake ${CMAKE_BINARY_DIR}/vsglConfigVersion.cmake
        DESTINATION ${VSGL_CMAKE_DIR})

configure_file(${CMAKE_SOURCE_DIR}/cmake/vsgl.pc.in ${CMAKE_BINARY_DIR}/vsgl.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/vsgl.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
