# stereo_add_library(NAME SOURCES...): the installable library stereo_NAME with its public
# headers in include/ beside the calling CMakeLists.txt, the alias stereo::NAME that the build
# links against, and the export name NAME, so that a consumer of the installed package links
# stereo::NAME too (cmake/install.cmake, docs/install.md).
function(stereo_add_library name)
  set(target stereo_${name})
  add_library(${target} ${ARGN})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  add_library(stereo::${name} ALIAS ${target})
endfunction()
