# Command-level tests of `abbe predict`. Included from tests/CMakeLists.txt to
# register the tests; the error cases run in script mode (cmake -P).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(ABBE_MACHINES ${CMAKE_CURRENT_SOURCE_DIR}/data/machines)

  # Worked examples 1 + 2 of docs/models.md at a CSV point, all three models:
  # htm (-2.5, 5, 3), ae-arm (2.28, -1, -5), dual = ae-arm + a small ε² part.
  add_test(NAME cli_predict_worked_example_all_models
           COMMAND $<TARGET_FILE:abbe> predict ${ABBE_MACHINES}/worked-example-points.csv
                   --machine ${ABBE_MACHINES}/worked-example.yaml --model all)
  set_tests_properties(cli_predict_worked_example_all_models PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "\n-300,-200,-250,2,-300\\.0025,-199\\.995,-249\\.997,-2\\.5,5,3,6\\.344289,-299\\.99772,-200\\.001,-250\\.005,2\\.28,-1,-5,5\\.585553,[^\n]*,-0\\.000025,0,-0\\.000021\n")

  # An NC program through the front end, summary only, JSON summary file.
  add_test(NAME cli_predict_nc_summary
           COMMAND $<TARGET_FILE:abbe> predict ${PROJECT_SOURCE_DIR}/nc-samples/thesis-toolpath-1.ngc
                   --machine ${ABBE_MACHINES}/sample.yaml --model all --summary-only
                   --summary-json ${CMAKE_CURRENT_BINARY_DIR}/cli_predict_summary.json)
  set_tests_properties(cli_predict_nc_summary PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION "[0-9]+ points.*\n.*\n  htm +cutting +[0-9]+ +[0-9.]+.*\n  htm +rapid +[0-9]+ +[0-9.]+.*\n  htm +all +[0-9]+ +[0-9.]+.*\n  ae-arm +cutting.*\n  ae-arm +rapid.*\n  ae-arm +all.*\n  dual +cutting +[0-9]+ +[0-9.]+")

  # JSON output: the points array and the summary.
  add_test(NAME cli_predict_json
           COMMAND $<TARGET_FILE:abbe> predict ${ABBE_MACHINES}/worked-example-points.csv
                   --machine ${ABBE_MACHINES}/worked-example.yaml --model dual --format json)
  set_tests_properties(cli_predict_json PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION "\\{\"points\": \\[\n\\{\"x\": -300, .*\"dual\": \\{\"px\": .*\"summary\": \\{")

  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_predict_errors cli_predict_work cli DEFINES -DMACHINES=${ABBE_MACHINES})
  return()
endif()

# ---- script mode: bad input gives exit code 1, names file and line, and
# leaves an existing output untouched ----
include(${CMAKE_CURRENT_LIST_DIR}/lib/refusal_helpers.cmake)
start_with_previous_output(${WORK}/out.csv)
function(expect_failure what pattern)
  refused_untouched(1 "${what}" "${pattern}" ${WORK}/out.csv
                    ${ABBE} predict ${ARGN} -o ${WORK}/out.csv)
  expect_no_temporary_files("${what}" ${WORK}/out.csv)
endfunction()

# out_of_range: error names the point's file and line, the axis and the range.
expect_failure("out of range" "narrow-points\\.csv:4 \\[X\\]: error: .*\\[-400, -200\\]"
               ${MACHINES}/narrow-points.csv --machine ${MACHINES}/narrow.yaml)

file(WRITE ${WORK}/bad-points.csv "x,y,z\n1,2,3\n1,2,zz\n")
expect_failure("bad points" "bad-points\\.csv:3:5 \\[z\\]: error: \"zz\" is not a finite number"
               ${WORK}/bad-points.csv --machine ${MACHINES}/worked-example.yaml)

file(WRITE ${WORK}/no-z.csv "x,y,dz\n1,2,3\n")
expect_failure("missing column" "no-z\\.csv:1.*no `z` column"
               ${WORK}/no-z.csv --machine ${MACHINES}/worked-example.yaml)

file(WRITE ${WORK}/bad.yaml "name: x\nchain: \"w X b X Z t\"\n")
expect_failure("bad machine" "bad\\.yaml:2:8 \\[chain\\]: error: invalid kinematic chain"
               ${MACHINES}/narrow-points.csv --machine ${WORK}/bad.yaml)

file(WRITE ${WORK}/bad.ngc "G21 G90\nG1 X10 Y10 F100\nG1 X20 Y&5\n")
expect_failure("bad program" "bad\\.ngc:3"
               ${WORK}/bad.ngc --machine ${MACHINES}/worked-example.yaml)

# A good run replaces the output.
execute_process(COMMAND ${ABBE} predict ${MACHINES}/worked-example-points.csv
                        --machine ${MACHINES}/worked-example.yaml -o ${WORK}/out.csv
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
file(READ ${WORK}/out.csv contents)
if(NOT rc EQUAL 0 OR NOT contents MATCHES "^x,y,z,px,py,pz,dx,dy,dz,d,line\n")
  message(FATAL_ERROR "good run: rc '${rc}', output:\n${contents}\n${err}")
endif()
if(NOT out MATCHES "ae-arm +all +2 +2\\.2800 +1\\.0000 +5\\.0000")
  message(FATAL_ERROR "good run: the summary (on stdout with -o FILE) is missing:\n${out}")
endif()

# A row with a number beyond the fast formatter (|v| ≥ 9e12) is written the
# long way, with the same columns; the rows around it keep the fast format
# (6 decimals, trailing zeros dropped) — CSV and JSON.
file(WRITE ${WORK}/huge.csv "x,y,z\n-300,-200,-250\n1e13,-200,-250\n-300.0000004,-199.9999996,-250\n")
execute_process(COMMAND ${ABBE} predict ${WORK}/huge.csv --machine ${MACHINES}/worked-example.yaml
                        -o ${WORK}/huge-out.csv
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
file(READ ${WORK}/huge-out.csv contents)
set(expected "x,y,z,px,py,pz,dx,dy,dz,d,line
-300,-200,-250,-299.99772,-200.001,-250.005,2.28,-1,-5,5.585553,2
10000000000000.000000,-200,-250,10000000000000.001953,-200.001,-100000250.008,2.28,-1,-100000000008,100000000008,3
-300,-200,-250,-299.99772,-200.001,-250.005,2.28,-1,-5,5.585553,4
")
if(NOT rc EQUAL 0 OR NOT contents STREQUAL expected)
  message(FATAL_ERROR "huge value: rc '${rc}', output:\n${contents}\nexpected:\n${expected}\n${err}")
endif()
execute_process(COMMAND ${ABBE} predict ${WORK}/huge.csv --machine ${MACHINES}/worked-example.yaml
                        --format json -o ${WORK}/huge-out.json
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
file(READ ${WORK}/huge-out.json contents)
if(NOT rc EQUAL 0 OR NOT contents MATCHES
   "\n\\{\"x\": 10000000000000\\.000000, \"y\": -200, \"z\": -250, \"line\": 3, \"ae-arm\": \\{\"px\": 10000000000000\\.001953, [^\n]*\"d\": 100000000008\\}\\},\n\\{\"x\": -300, ")
  message(FATAL_ERROR "huge value (JSON): rc '${rc}', output:\n${contents}\n${err}")
endif()
