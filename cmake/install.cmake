# The installable package (issue 23): `cmake --install build --prefix P` puts the libraries
# stereo_model, stereo_io and stereo_robot, their public headers and the `stereo` tool under P,
# with P/lib/cmake/stereo/stereo-config.cmake so that a consumer writes
#   find_package(stereo 0.1 REQUIRED)                    # every component
#   find_package(stereo 0.1 REQUIRED COMPONENTS model)   # stereo::model alone: no OpenCV
#   target_link_libraries(app PRIVATE stereo::io)        # or stereo::model, stereo::robot
# Each library is a component with its own export file (stereo-model-targets.cmake, ...), and
# the config file finds the third-party packages of the requested components only (issue 47).
# examples/consumer/ is such a consumer; the test install.consumer builds it against a fresh
# install, and a model-only consumer where OpenCV cannot be found. The Verilated RTL
# (stereo_sim) is not exported: its headers are generated into the build tree; FPGA integrators
# take the RTL from rtl/ (docs/install.md).
include(CMakePackageConfigHelpers)

set(STEREO_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/stereo)

# A build tuned to this machine's CPU (STEREO_NATIVE, -march=native) is for local runs and
# benchmarks: what it installs might not run on another CPU, so it refuses to install. The
# check runs first, before any file is copied.
if(STEREO_NATIVE)
  install(CODE "message(FATAL_ERROR \"stereo: this build was configured with STEREO_NATIVE=ON \
(-march=native): its libraries and tool may not run on another CPU and are not installed. \
Configure a portable build to install (STEREO_NATIVE=OFF, the default; docs/install.md).\")")
endif()

# One export set per component: a consumer that asks for `model` loads no file that names an
# OpenCV target, so it needs no OpenCV.
foreach(component IN ITEMS model io robot)
  install(TARGETS stereo_${component}
          EXPORT stereo-${component}-targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT stereo-${component}-targets NAMESPACE stereo::
          DESTINATION ${STEREO_INSTALL_CMAKEDIR})
endforeach()
install(TARGETS stereo RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The test helpers beside the public headers (stereo_io/test_support.hpp, test_compare.hpp: the
# stereo_test_support target's) are not part of the package (issue 47).
install(DIRECTORY ${CMAKE_SOURCE_DIR}/model/include/ ${CMAKE_SOURCE_DIR}/io/include/
                  ${CMAKE_SOURCE_DIR}/robot/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        PATTERN "test_*.hpp" EXCLUDE)
install(FILES ${CMAKE_BINARY_DIR}/generated/include/stereo/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stereo)

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/stereo-config.cmake.in
                              ${CMAKE_BINARY_DIR}/stereo-config.cmake
                              INSTALL_DESTINATION ${STEREO_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/stereo-config-version.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/stereo-config.cmake ${CMAKE_BINARY_DIR}/stereo-config-version.cmake
        DESTINATION ${STEREO_INSTALL_CMAKEDIR})
