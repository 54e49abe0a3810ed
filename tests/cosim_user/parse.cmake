# cmake -DSPEC=... -P parse.cmake: prints what sim/cosim_user.cmake makes of a
# -DSTEREO_COSIM_USER value (tests/CMakeLists.txt, label "sim"), or its error.
include(${CMAKE_CURRENT_LIST_DIR}/../../sim/cosim_user.cmake)
stereo_parse_cosim_user("${SPEC}" user)
message("user: ${user_WIDTH} ${user_HEIGHT} ${user_NDISP} ${user_WINDOW} ${user_LANES} "
        "${user_MAX_MIN_DISP}")
