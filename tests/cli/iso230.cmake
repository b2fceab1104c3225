# Command-level tests of `abbe iso230` (label cli). Included from
# tests/CMakeLists.txt to register the tests; run with `cmake -P` for the
# exit-code checks.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(ABBE_ISO230_DATA ${PROJECT_SOURCE_DIR}/tests/data/iso230)
  # The hand-computed example of tests/unit/iso230_test.cpp as a text table.
  add_test(NAME cli_iso230_text COMMAND $<TARGET_FILE:abbe> iso230 ${ABBE_ISO230_DATA}/hand.csv)
  set_tests_properties(cli_iso230_text PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "X +EXX +µm +2 +3 +9\\.000 +6\\.000 +-0\\.500 +3\\.500 +2\\.000 +5\\.000\nX +EBX +µrad +2 +2 +- +- +- +- +- +-\n")
  add_test(NAME cli_iso230_json
           COMMAND $<TARGET_FILE:abbe> iso230 ${ABBE_ISO230_DATA}/hand.csv --per-target)
  set_tests_properties(cli_iso230_json PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION "\"B_mean\": -0\\.5,.*\"R\": 6\\.0,.*\"targets\": \\[.*\"R\": null")
  add_test(NAME cli_iso230_errors
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DDATA=${ABBE_ISO230_DATA} -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_iso230_errors -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_iso230_errors PROPERTIES LABELS cli)
  return()
endif()

include(${SRC}/tests/cli/lib/script_helpers.cmake)

expect_failure("bad-direction.csv:3:11 [direction]: error: direction 'sideways'"
               ${ABBE} iso230 ${DATA}/bad-direction.csv)
expect_failure("EYY target -25: 1 up run(s)" ${ABBE} iso230 ${DATA}/one-run.csv)
expect_failure("cannot open" ${ABBE} iso230 ${DATA}/no-such-file.csv)
# A failed run leaves an existing output untouched.
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/out.txt "previous\n")
expect_failure("[direction]" ${ABBE} iso230 ${DATA}/bad-direction.csv -o ${WORK}/out.txt)
file(READ ${WORK}/out.txt kept)
if(NOT kept STREQUAL "previous\n")
  message(FATAL_ERROR "the existing output was changed")
endif()
file(REMOVE_RECURSE ${WORK})
