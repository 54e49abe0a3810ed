# The API reference (docs/install.md, "API reference"): `cmake --build build --target api_docs`
# runs Doxygen (Debian's doxygen) on the installed public headers (model/include, io/include,
# robot/include, without the test helpers) into build/docs/api/html/index.html. Not part of the
# default build. Without doxygen the target is not defined. The ctest docs.api_reference (label
# docs) builds it and fails on any Doxygen warning.
find_program(STEREO_DOXYGEN doxygen)
if(NOT STEREO_DOXYGEN)
  message(STATUS "doxygen not found (apt-get install doxygen): no api_docs target")
  return()
endif()
find_package(Python3 COMPONENTS Interpreter QUIET)
if(NOT Python3_Interpreter_FOUND)
  message(STATUS "python3 not found (docs/api/comment_filter.py): no api_docs target")
  return()
endif()

set(STEREO_API_DOCS_DIR ${CMAKE_BINARY_DIR}/docs/api)
set(STEREO_API_DOCS_INPUT
    "${CMAKE_SOURCE_DIR}/model/include ${CMAKE_SOURCE_DIR}/io/include ${CMAKE_SOURCE_DIR}/robot/include ${CMAKE_BINARY_DIR}/generated/include ${CMAKE_SOURCE_DIR}/docs/api/mainpage.md")
set(STEREO_API_DOCS_STRIP
    "${CMAKE_SOURCE_DIR}/model/include ${CMAKE_SOURCE_DIR}/io/include ${CMAKE_SOURCE_DIR}/robot/include ${CMAKE_BINARY_DIR}/generated/include")
set(STEREO_API_DOCS_FILTER "${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/docs/api/comment_filter.py")
configure_file(${CMAKE_SOURCE_DIR}/docs/api/Doxyfile.in ${STEREO_API_DOCS_DIR}/Doxyfile @ONLY)

file(GLOB_RECURSE stereo_api_headers CONFIGURE_DEPENDS
     ${CMAKE_SOURCE_DIR}/model/include/*.hpp ${CMAKE_SOURCE_DIR}/io/include/*.hpp
     ${CMAKE_SOURCE_DIR}/robot/include/*.hpp)
add_custom_command(
  OUTPUT ${STEREO_API_DOCS_DIR}/html/index.html
  COMMAND ${CMAKE_COMMAND} -E remove_directory ${STEREO_API_DOCS_DIR}/html
  COMMAND ${STEREO_DOXYGEN} ${STEREO_API_DOCS_DIR}/Doxyfile
  DEPENDS ${stereo_api_headers} ${CMAKE_SOURCE_DIR}/docs/api/comment_filter.py
          ${CMAKE_SOURCE_DIR}/docs/api/mainpage.md
          ${STEREO_API_DOCS_DIR}/Doxyfile
  WORKING_DIRECTORY ${STEREO_API_DOCS_DIR}
  COMMENT "API reference (Doxygen): ${STEREO_API_DOCS_DIR}/html/index.html"
  VERBATIM)
add_custom_target(api_docs DEPENDS ${STEREO_API_DOCS_DIR}/html/index.html)

if(STEREO_BUILD_TESTS)
  add_test(NAME docs.api_reference
           COMMAND sh ${CMAKE_SOURCE_DIR}/docs/api/check_api_docs.sh ${CMAKE_BINARY_DIR}
                   ${STEREO_API_DOCS_DIR})
  set_tests_properties(docs.api_reference PROPERTIES LABELS docs TIMEOUT 600)
endif()
