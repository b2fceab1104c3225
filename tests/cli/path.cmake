# Command-level tests of `abbe path`. Included from tests/CMakeLists.txt to
# register the tests; run with `cmake -P` (script mode) by the atomic-output
# test below.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(ABBE_PATH_SAMPLES ${PROJECT_SOURCE_DIR}/nc-samples)

  # Every sample fragments without error (tool 1 = 200 mm, see docs/samples.md).
  file(GLOB abbe_path_sample_files CONFIGURE_DEPENDS ${ABBE_PATH_SAMPLES}/*.ngc)
  foreach(sample ${abbe_path_sample_files})
    get_filename_component(sample_name ${sample} NAME_WE)
    add_test(NAME cli_path_sample_${sample_name}
             COMMAND $<TARGET_FILE:abbe> path ${sample} --tool 1=200 --count)
    set_tests_properties(cli_path_sample_${sample_name} PROPERTIES
      LABELS cli PASS_REGULAR_EXPRESSION "points=[1-9][0-9]*")
  endforeach()

  # CSV to stdout: header, the rectangle's far corner at Z -280 with L = 200.
  add_test(NAME cli_path_csv_stdout
           COMMAND $<TARGET_FILE:abbe> path ${ABBE_PATH_SAMPLES}/thesis-toolpath-1.ngc --tool 1=200)
  set_tests_properties(cli_path_csv_stdout PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION "^x,y,z,tool_length,line,kind,feed,time,vx,vy,vz\n.*\n-650,-350,-280,200,[0-9]+,linear,1000,")

  # JSON: a streamed array of objects.
  add_test(NAME cli_path_json
           COMMAND $<TARGET_FILE:abbe> path ${ABBE_PATH_SAMPLES}/thesis-toolpath-2.ngc --tool 1=200
                   --format json -o -)
  set_tests_properties(cli_path_json PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION "^\\[\n\\{\"x\":.*\"kind\":\"arc\".*\n\\]\n$")

  # A missing or bad program: exit code 1, an error naming file and line, the existing
  # output untouched and no temporary file left; a good run replaces it.
  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_path_bad_program_atomic_output cli_path_work cli
                  DEFINES -DSAMPLE=${ABBE_PATH_SAMPLES}/thesis-toolpath-1.ngc)
  return()
endif()

# ---- script mode ----
include(${CMAKE_CURRENT_LIST_DIR}/lib/refusal_helpers.cmake)
start_with_previous_output(${WORK}/out.csv)
file(WRITE ${WORK}/bad.ngc "G21 G90\nG1 X10 Y10 F100\nG1 X20 Y&5\n")

execute_process(COMMAND ${ABBE} path ${WORK}/no-such-program.ngc -o ${WORK}/out.csv
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 1 OR NOT err MATCHES "no-such-program\\.ngc")
  message(FATAL_ERROR "missing program: expected exit code 1 and the file named, got '${rc}'\n${err}")
endif()

# bad.ngc line 3 named, the existing output untouched.
refused_untouched(1 "bad program" "bad\\.ngc:3" ${WORK}/out.csv
                  ${ABBE} path ${WORK}/bad.ngc -o ${WORK}/out.csv)
expect_no_temporary_files("bad program" ${WORK}/out.csv)

execute_process(COMMAND ${ABBE} path ${SAMPLE} --tool 1=200 -o ${WORK}/out.csv RESULT_VARIABLE rc
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "good program: exit code ${rc}\n${err}")
endif()
file(STRINGS ${WORK}/out.csv rows)
list(LENGTH rows n)
list(GET rows 0 header)
if(NOT header STREQUAL "x,y,z,tool_length,line,kind,feed,time,vx,vy,vz" OR n LESS 200)
  message(FATAL_ERROR "good program: unexpected output (${n} rows, header '${header}')")
endif()
expect_no_temporary_files("good program" ${WORK}/out.csv)
file(REMOVE_RECURSE ${WORK})
