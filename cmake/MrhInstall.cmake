# SPDX-License-Identifier: Apache-2.0
# `make install` / `cmake --install`: headers, the module libraries and a CMake package config so
# that `find_package(mrhaptics)` gives the target mrhaptics::mrhaptics.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# MuJoCo travels with the package: its library beside the module libraries, found by installed
# binaries through $ORIGIN/../lib and by consumers through mrhapticsConfig.cmake (mujoco::mujoco).
install(FILES ${MRH_MUJOCO_LIBRARY} DESTINATION ${CMAKE_INSTALL_LIBDIR})
set(MRH_MUJOCO_LIBRARY_NAME libmujoco.so.${MRH_MUJOCO_VERSION})

get_property(mrh_modules GLOBAL PROPERTY MRH_MODULES)

# The modules apart from the library (experiments, psychophysics) and the viewer, which the
# package does not ship a library for, stay out of it: every installed header has its library.
install(DIRECTORY include/mrh DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        PATTERN experiments EXCLUDE PATTERN psychophysics EXCLUDE PATTERN viewer EXCLUDE)
install(TARGETS mrhaptics ${mrh_modules} EXPORT mrhapticsTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT mrhapticsTargets NAMESPACE mrhaptics::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mrhaptics)
configure_package_config_file(cmake/mrhapticsConfig.cmake.in
  ${PROJECT_BINARY_DIR}/mrhapticsConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mrhaptics)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mrhapticsConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/mrhapticsConfig.cmake
              ${PROJECT_BINARY_DIR}/mrhapticsConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mrhaptics)
if(TARGET mrh)
  install(TARGETS mrh RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(DIRECTORY scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mrhaptics/scenes)
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} OPTIONAL)
