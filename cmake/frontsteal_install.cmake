# frontsteal_install.cmake — what `cmake --install <build> [--prefix P]` puts under P, so that another project
# can `find_package(frontsteal)` and link frontsteal::core, ::schedulers, ::tessellate, ::reporting, ::measure or
# ::relacy_backend
# (examples/ are two such projects; tests/install/consume_installed.cmake builds them against an install).
#
#   include/frontsteal/{core,schedulers,tessellate,reporting,measure,models_check}/*.hpp  the headers, repository paths
#   lib/libfrontsteal_{schedulers,tessellate,reporting,measure}.a      the four compiled libraries
#   lib/cmake/frontsteal/                                              config, version and target files
#
# Only these six targets are exported. Executables, the CAD importer (Open CASCADE), the renderer (EGL, GL)
# and the test libraries stay in the build tree, so none of their dependencies reach a consumer: the export
# needs Threads, TBB and OpenMP (linked privately into the static frontsteal::schedulers, so they appear as
# link-only dependencies), glm (frontsteal::tessellate's public headers), CGAL (linked privately into the static
# frontsteal::tessellate: link-only), nlohmann_json and CLI11 (frontsteal::reporting's public headers).
include(CMakePackageConfigHelpers)

set(FRONTSTEAL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/frontsteal)

install(TARGETS frontsteal_core frontsteal_schedulers frontsteal_tessellate frontsteal_reporting frontsteal_measure
        EXPORT frontsteal-targets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})  # include dirs: $<INSTALL_INTERFACE:> on each target
install(EXPORT frontsteal-targets NAMESPACE frontsteal:: DESTINATION ${FRONTSTEAL_INSTALL_CMAKEDIR})

# Headers by directory (non-recursive: benchmarks/, fuzz/ and the main job's schedulers/main_job/ stay out: the
# frontsteal executable's pieces are not a library), so a header added to one of these directories is installed
# without editing this file. The Open CASCADE importer's headers are left out: its library is not installed.
foreach(_dir core schedulers tessellate reporting measure)
  file(GLOB _headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${_dir}/*.hpp)
  list(FILTER _headers EXCLUDE REGEX "/(occt_import|isolated_import)\\.hpp$")
  install(FILES ${_headers} DESTINATION ${FRONTSTEAL_INSTALL_INCLUDEDIR}/${_dir})
endforeach()

# The checker pieces: the Relacy backend and, for a protocol variant given as a table of orders (TablePolicy),
# the protocol suite with its scenarios and search settings (models_check/protocol_suite.hpp: simulate_suite).
# A separate export set, so that the package works without Relacy: frontsteal-config.cmake loads it only where
# Relacy's headers are found.
if(TARGET frontsteal_relacy_backend)
  install(TARGETS frontsteal_relacy_backend EXPORT frontsteal-relacy-targets)
  install(EXPORT frontsteal-relacy-targets NAMESPACE frontsteal:: DESTINATION ${FRONTSTEAL_INSTALL_CMAKEDIR})
  install(FILES ${PROJECT_SOURCE_DIR}/models_check/relacy_backend.hpp
                ${PROJECT_SOURCE_DIR}/models_check/protocol_suite.hpp
                ${PROJECT_SOURCE_DIR}/models_check/scenarios.hpp
                ${PROJECT_SOURCE_DIR}/models_check/search.hpp
                ${PROJECT_SOURCE_DIR}/models_check/table_policy.hpp
          DESTINATION ${FRONTSTEAL_INSTALL_INCLUDEDIR}/models_check)
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/frontsteal-config.cmake.in
                              ${PROJECT_BINARY_DIR}/frontsteal-config.cmake
                              INSTALL_DESTINATION ${FRONTSTEAL_INSTALL_CMAKEDIR})
# 0.x: SameMajorVersion accepts any 0.y; the major number goes to 1 when the interface is frozen.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/frontsteal-config-version.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/frontsteal-config.cmake ${PROJECT_BINARY_DIR}/frontsteal-config-version.cmake
        DESTINATION ${FRONTSTEAL_INSTALL_CMAKEDIR})
