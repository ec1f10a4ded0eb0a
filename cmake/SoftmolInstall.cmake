# cmake/SoftmolInstall.cmake — what `cmake --install` puts under the prefix: the public headers
# (include/softmol/), libsoftmol.so, the CMake package (find_package(softmol) gives
# softmol::softmol; with a version file), softmol.pc for pkg-config, the `softmol` command and
# the OpenImageIO module beside it (lib/softmol/, where io/oiio_loader.cpp looks).
include(CMakePackageConfigHelpers)
set(SOFTMOL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/softmol)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/softmol DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS softmol_api EXPORT softmolTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS softmol_oiio_module LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/softmol)
install(EXPORT softmolTargets NAMESPACE softmol:: DESTINATION ${SOFTMOL_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/softmolConfig.cmake.in
  ${PROJECT_BINARY_DIR}/softmolConfig.cmake INSTALL_DESTINATION ${SOFTMOL_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/softmolConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)  # 0.x: a minor version may break the API
install(FILES ${PROJECT_BINARY_DIR}/softmolConfig.cmake ${PROJECT_BINARY_DIR}/softmolConfigVersion.cmake
  DESTINATION ${SOFTMOL_CMAKE_DIR})

file(RELATIVE_PATH SOFTMOL_PC_TO_PREFIX /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
configure_file(${PROJECT_SOURCE_DIR}/cmake/softmol.pc.in ${PROJECT_BINARY_DIR}/softmol.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/softmol.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
