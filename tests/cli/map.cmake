# Command-level tests of `abbe map` (label cli): the sample machine's
# volumetric error, htm vs ae-arm, slices, and bad options.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_map_sample
           COMMAND $<TARGET_FILE:abbe> map --machine ${PROJECT_SOURCE_DIR}/machines/sample/machine.yaml
                   --grid 100)
  set_tests_properties(cli_map_sample PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "11 × 6 × 6 = 396 grid points(.*\n)*  htm +[0-9.]+ +[0-9.]+ +[0-9.]+\n  ae-arm .*\n  dual .*second order: max [0-9.]+.*\n  htm vs ae-arm: mean \\|d\\| [0-9.]+ µm larger with htm; ae-arm mean [0-9.]+ % smaller")

  add_test(NAME cli_map_files
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_map -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_map_files PROPERTIES LABELS cli)
  return()
endif()

include(${SRC}/tests/cli/lib/script_helpers.cmake)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(M ${SRC}/machines/sample/machine.yaml)

run(${ABBE} map --machine ${M} --box -600,-300,-400,-400,-200,-300 --grid 100 --model ae-arm
    -o ${WORK}/map.csv --slices ${WORK}/slices --json ${WORK}/map.json)
file(STRINGS ${WORK}/map.csv lines)
list(LENGTH lines n)
if(NOT n EQUAL 13)  # header + 3 × 2 × 2 points
  message(FATAL_ERROR "map.csv: ${n} lines, expected 13")
endif()
list(GET lines 0 header)
if(NOT header STREQUAL "x,y,z,ae-arm_dx,ae-arm_dy,ae-arm_dz,ae-arm_d")
  message(FATAL_ERROR "map.csv header: ${header}")
endif()
foreach(f xy_z-400.csv xy_z-300.csv xz_y-200.csv yz_x-500.csv)
  if(NOT EXISTS ${WORK}/slices/${f})
    message(FATAL_ERROR "missing slice ${f}")
  endif()
endforeach()
file(READ ${WORK}/map.json js)
if(NOT js MATCHES "\"model\": \"ae-arm\"")
  message(FATAL_ERROR "map.json: ${js}")
endif()

expect_failure("--box" ${ABBE} map --machine ${M} --box 0,0,0,-1,1,1)
expect_failure("--grid" ${ABBE} map --machine ${M} --grid 0)
expect_failure("no-such.yaml" ${ABBE} map --machine ${WORK}/no-such.yaml)
