# What `cmake --install` puts under the prefix: bin/rupture; the libraries, their headers
# (include/rupture/<concept>/*.hpp) and a CMake package, so that another project's
# find_package(rupture) links rupture::fbm, rupture::analysis, ...; and the Python package
# (src/python/CMakeLists.txt). Nothing needs root: any prefix works.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS rupture RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

set(rupture_libraries core io fbm analysis sample dem loading scan figures report)
foreach(name IN LISTS rupture_libraries)
  set_target_properties(rupture_${name} PROPERTIES EXPORT_NAME ${name})
  list(APPEND rupture_library_targets rupture_${name})
endforeach()
install(TARGETS ${rupture_library_targets} EXPORT ruptureTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rupture)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rupture
        FILES_MATCHING PATTERN "*.hpp" PATTERN "cli" EXCLUDE PATTERN "python" EXCLUDE)
install(FILES ${CMAKE_BINARY_DIR}/generated/rupture/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rupture/rupture)

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/rupture)
install(EXPORT ruptureTargets NAMESPACE rupture:: DESTINATION ${config_dir})
get_target_property(scan_links rupture_scan LINK_LIBRARIES)
if("MPI::MPI_CXX" IN_LIST scan_links)  # the scan's MPI farm (src/scan) needs MPI in a consumer's link too
  set(RUPTURE_WITH_MPI ON)
else()
  set(RUPTURE_WITH_MPI OFF)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/rupture-config.cmake.in
  ${CMAKE_BINARY_DIR}/rupture-config.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/rupture-config-version.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/rupture-config.cmake ${CMAKE_BINARY_DIR}/rupture-config-version.cmake
        DESTINATION ${config_dir})
