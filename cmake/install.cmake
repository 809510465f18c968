# SPDX-License-Identifier: BSD-3-Clause
# Install rules: the libraries as hybridcd::core, hybridcd::ompl and hybridcd::fcl (those built),
# their public headers, the command-line tool, a CMake package (find_package(hybridcd)) and
# pkg-config files (hybridcd, hybridcd-ompl).

set(HYBRIDCD_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/hybridcd" CACHE STRING
    "Where hybridcdConfig.cmake is installed, relative to the prefix")

set(_hybridcd_targets hybridcd_core)
set(HYBRIDCD_COMPONENTS core)
if(TARGET hybridcd_ompl)
  list(APPEND _hybridcd_targets hybridcd_ompl)
  list(APPEND HYBRIDCD_COMPONENTS ompl)
endif()
if(TARGET hybridcd_fcl)
  list(APPEND _hybridcd_targets hybridcd_fcl)
  list(APPEND HYBRIDCD_COMPONENTS fcl)
endif()

# Shared libraries find each other, and the tool finds them, wherever the prefix is.
if(BUILD_SHARED_LIBS AND NOT IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}" AND NOT IS_ABSOLUTE "${CMAKE_INSTALL_BINDIR}")
  file(RELATIVE_PATH _hybridcd_bin_to_lib "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${CMAKE_INSTALL_LIBDIR}")
  set_target_properties(${_hybridcd_targets} PROPERTIES INSTALL_RPATH "$ORIGIN")
  if(TARGET hybridcd)
    set_target_properties(hybridcd PROPERTIES INSTALL_RPATH "$ORIGIN/${_hybridcd_bin_to_lib}")
  endif()
endif()

install(TARGETS ${_hybridcd_targets} EXPORT hybridcdTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET hybridcd)
  install(TARGETS hybridcd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

# Public headers: all of include/hybridcd, less the layers that were not built.
# render/ belongs to the tool (its library is not installed).
set(_hybridcd_header_excludes PATTERN render EXCLUDE)
if(NOT TARGET hybridcd_ompl)
  list(APPEND _hybridcd_header_excludes PATTERN ompl EXCLUDE PATTERN planners EXCLUDE)
endif()
if(NOT TARGET hybridcd_fcl)
  list(APPEND _hybridcd_header_excludes PATTERN fcl EXCLUDE)
endif()
install(DIRECTORY include/hybridcd DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h" ${_hybridcd_header_excludes})

# A static core carries its private dependencies into the consumer's link line, so the package
# must find them too; a shared one does not.
get_target_property(_hybridcd_core_type hybridcd_core TYPE)
if(_hybridcd_core_type STREQUAL "STATIC_LIBRARY")
  set(HYBRIDCD_STATIC ON)
else()
  set(HYBRIDCD_STATIC OFF)
endif()

install(EXPORT hybridcdTargets NAMESPACE hybridcd:: DESTINATION ${HYBRIDCD_INSTALL_CMAKEDIR})
configure_package_config_file(cmake/hybridcdConfig.cmake.in
  "${PROJECT_BINARY_DIR}/hybridcdConfig.cmake"
  INSTALL_DESTINATION ${HYBRIDCD_INSTALL_CMAKEDIR})
write_basic_package_version_file("${PROJECT_BINARY_DIR}/hybridcdConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/hybridcdConfig.cmake" "${PROJECT_BINARY_DIR}/hybridcdConfigVersion.cmake"
  DESTINATION ${HYBRIDCD_INSTALL_CMAKEDIR})

# pkg-config: paths relative to the .pc file, so the prefix given to `cmake --install --prefix`
# is honoured.
set(HYBRIDCD_PKGCONFIGDIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
if(IS_ABSOLUTE "${HYBRIDCD_PKGCONFIGDIR}")
  set(HYBRIDCD_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _hybridcd_up "/prefix/${HYBRIDCD_PKGCONFIGDIR}" "/prefix")
  string(REGEX REPLACE "/$" "" _hybridcd_up "${_hybridcd_up}")
  set(HYBRIDCD_PC_PREFIX "\${pcfiledir}/${_hybridcd_up}")
endif()
foreach(_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_dir}}")
    set(HYBRIDCD_PC_${_dir} "${CMAKE_INSTALL_${_dir}}")
  else()
    set(HYBRIDCD_PC_${_dir} "\${prefix}/${CMAKE_INSTALL_${_dir}}")
  endif()
endforeach()
# Dependencies the linker needs: public ones always, private ones too when the core is static.
if(HYBRIDCD_STATIC)
  set(HYBRIDCD_PC_REQUIRES "Requires: eigen3 assimp nlopt qhull_r libhwy")
else()
  set(HYBRIDCD_PC_REQUIRES "Requires: eigen3\nRequires.private: assimp nlopt qhull_r libhwy")
endif()
configure_file(cmake/hybridcd.pc.in "${PROJECT_BINARY_DIR}/hybridcd.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/hybridcd.pc" DESTINATION ${HYBRIDCD_PKGCONFIGDIR})
if(TARGET hybridcd_ompl)
  configure_file(cmake/hybridcd-ompl.pc.in "${PROJECT_BINARY_DIR}/hybridcd-ompl.pc" @ONLY)
  install(FILES "${PROJECT_BINARY_DIR}/hybridcd-ompl.pc" DESTINATION ${HYBRIDCD_PKGCONFIGDIR})
endif()
