# Command-level tests of `abbe report` and of the CLI's help texts. Included
# from tests/CMakeLists.txt; the checks of the written pages run in script
# mode (cmake -P).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_report
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_report_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_report PROPERTIES LABELS cli TIMEOUT 300)

  add_test(NAME cli_help_footer COMMAND $<TARGET_FILE:abbe> --help)
  set_tests_properties(cli_help_footer PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION "Examples:.*abbe report predict.*Exit codes: 0 ok, 1 bad input.*2 usage, 3 internal")
  foreach(cmd path interpret predict simulate iso230)
    add_test(NAME cli_help_example_${cmd} COMMAND $<TARGET_FILE:abbe> ${cmd} --help)
    set_tests_properties(cli_help_example_${cmd} PROPERTIES LABELS cli
      PASS_REGULAR_EXPRESSION "Example: abbe ${cmd} ")
  endforeach()
  add_test(NAME cli_help_example_report COMMAND $<TARGET_FILE:abbe> report predict --help)
  set_tests_properties(cli_help_example_report PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION "Example: abbe report predict ")
  return()
endif()

# ---- script mode ----
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(MACHINE ${SRC}/tests/data/machines/sample.yaml)

function(run_ok what)
  execute_process(COMMAND ${ABBE} ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}: exit code ${rc}\n${err}")
  endif()
  # stderr is not a terminal here: no progress bar (no carriage returns).
  if(err MATCHES "\r")
    message(FATAL_ERROR "${what}: progress output on a non-terminal stderr:\n${err}")
  endif()
endfunction()

function(expect_in file what)
  file(READ ${file} html)
  foreach(s ${ARGN})
    string(FIND "${html}" "${s}" pos)
    if(pos EQUAL -1)
      message(FATAL_ERROR "${what}: '${s}' not found in ${file}")
    endif()
  endforeach()
  if(html MATCHES "=\"[^\"]*[^a-z]nan[^a-z]" OR html MATCHES "=\"-?inf")
    message(FATAL_ERROR "${what}: NaN or inf in an attribute of ${file}")
  endif()
endfunction()

# predict report of a thesis toolpath, all models.
run_ok("report predict" report predict ${SRC}/nc-samples/thesis-toolpath-1.ngc
       --machine ${MACHINE} --model all --exaggerate 2000 --tolerance 20 -o ${WORK}/predict.html)
expect_in(${WORK}/predict.html "report predict"
  "<!DOCTYPE html>" "id=\"summary-table\"" "id=\"toolpath-3d\"" "id=\"toolpath-3d-data\""
  "id=\"toolpath-3d-tol\" min=\"0\" step=\"any\" value=\"20\"" "{\"k\":2000,\"tol\":20,"
  "\"18\":\"G1 X-650 F1000\"" "id=\"deviation-htm\"" "id=\"deviation-ae-arm\""
  "id=\"deviation-dual\"" ">path length (mm)</text>" ">deviation (µm)</text>"
  "<title>line 18: G1 X-650 F1000" "<footer id=\"provenance\">"
  "report predict ${SRC}/nc-samples/thesis-toolpath-1.ngc")
# Bounded: the 23-line program's report stays small.
file(SIZE ${WORK}/predict.html predict_size)
if(predict_size GREATER 307200)
  message(FATAL_ERROR "the predict report of thesis-toolpath-1.ngc is ${predict_size} bytes (> 300 kB)")
endif()
# The footer holds the SHA-256 of the inputs.
file(SHA256 ${SRC}/nc-samples/thesis-toolpath-1.ngc program_sha)
file(SHA256 ${MACHINE} machine_sha)
expect_in(${WORK}/predict.html "report predict footer" "${program_sha}" "${machine_sha}")
# The summary table agrees with `abbe predict` on the same program.
execute_process(COMMAND ${ABBE} predict ${SRC}/nc-samples/thesis-toolpath-1.ngc --machine ${MACHINE}
                        --model ae-arm --summary-only OUTPUT_VARIABLE summary RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT summary MATCHES "ae-arm +cutting +[0-9]+ +([0-9.]+) +([0-9.]+) +([0-9.]+) +([0-9.]+) +([0-9.]+)")
  message(FATAL_ERROR "abbe predict summary: ${summary}")
endif()
set(rms ${CMAKE_MATCH_4})
set(maxd ${CMAKE_MATCH_5})
file(READ ${WORK}/predict.html html)
if(NOT html MATCHES "<td>ae-arm</td><td>cutting</td><td>[0-9]+</td><td>[0-9.]+</td><td>[0-9.]+</td><td>[0-9.]+</td><td>([0-9.]+)</td><td>([0-9.]+)</td>")
  message(FATAL_ERROR "no ae-arm cutting row in the summary table")
endif()
string(SUBSTRING "${CMAKE_MATCH_2}" 0 5 a)
string(SUBSTRING "${maxd}" 0 5 b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "max |d| of ae-arm: report ${CMAKE_MATCH_2}, predict ${maxd}")
endif()

# From standard input, to standard output.
execute_process(COMMAND ${ABBE} report predict - --machine ${MACHINE} --model htm -o -
                INPUT_FILE ${SRC}/nc-samples/thesis-toolpath-2.ngc
                OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^<!DOCTYPE html>.*id=\"deviation-htm\".*</html>\n$")
  message(FATAL_ERROR "report predict - -o -: exit ${rc}")
endif()

# map report.
run_ok("report map" report map --machine ${MACHINE} --grid 100 -o ${WORK}/map.html)
expect_in(${WORK}/map.html "report map"
  "id=\"map-table\"" "id=\"map-htm-xy0\"" "id=\"map-ae-arm-xy0\"" "class=\"scale-bar\""
  ">|d| (µm)</text>" "htm against ae-arm")

# compensate report: the output of abbe compensate against the original.
run_ok("compensate" compensate ${SRC}/nc-samples/thesis-toolpath-1.ngc --machine ${MACHINE}
       -o ${WORK}/comp.ngc)
run_ok("report compensate" report compensate ${SRC}/nc-samples/thesis-toolpath-1.ngc
       --compensated ${WORK}/comp.ngc --machine ${MACHINE} -o ${WORK}/compensation.html)
expect_in(${WORK}/compensation.html "report compensate"
  "id=\"compensate-table\"" "id=\"compensate-iso\"" "id=\"compensate-xy\""
  "id=\"compensate-deviation\"" "predicted compensated (×")
file(READ ${WORK}/compensation.html html)
if(NOT html MATCHES "<td>original: predicted deviation \\|d\\|</td><td>cutting</td><td>[0-9]+</td><td>([0-9]+)\\.[0-9]+</td>")
  message(FATAL_ERROR "report compensate: no cutting row of the original")
endif()
set(rms_original ${CMAKE_MATCH_1})
if(NOT html MATCHES "<td>compensated: predicted → nominal path \\(abbe verify\\)</td><td>cutting</td><td>([0-9]+)</td><td>([0-9]+)\\.[0-9]+</td><td>([0-9.]+)</td>")
  message(FATAL_ERROR "report compensate: no cutting row of the compensated program")
endif()
if(NOT CMAKE_MATCH_2 LESS rms_original)
  message(FATAL_ERROR "report compensate: rms ${CMAKE_MATCH_2} µm not below the original's ${rms_original}")
endif()
# One answer: the report's cutting row is abbe verify's (points and max).
set(report_points ${CMAKE_MATCH_1})
set(report_max ${CMAKE_MATCH_3})
execute_process(COMMAND ${ABBE} verify ${WORK}/comp.ngc --against ${SRC}/nc-samples/thesis-toolpath-1.ngc
                        --machine ${MACHINE} OUTPUT_VARIABLE vout RESULT_VARIABLE rc)
if(NOT vout MATCHES "cutting moves, predicted compensated -> nominal: ([0-9]+) points, max ([0-9]+)\\.([0-9][0-9][0-9][0-9])")
  message(FATAL_ERROR "abbe verify: ${vout}")
endif()
# verify prints 4 decimals, the report 3: compare in units of 0.001 µm, rounded.
math(EXPR verify_max_1000 "(${CMAKE_MATCH_2}${CMAKE_MATCH_3} + 5) / 10")
string(REPLACE "." "" report_max_1000 "${report_max}")
math(EXPR report_max_1000 "${report_max_1000}")
if(NOT CMAKE_MATCH_1 EQUAL report_points OR NOT verify_max_1000 EQUAL report_max_1000)
  message(FATAL_ERROR "report compensate (${report_points} points, max ${report_max}) and abbe verify (${CMAKE_MATCH_1}, ${CMAKE_MATCH_2}.${CMAKE_MATCH_3}) disagree")
endif()

# diagnose report on the sample machine's measured grid.
run_ok("report diagnose" report diagnose --measured ${SRC}/machines/sample/measured-grid.csv
       --machine ${SRC}/machines/sample/machine.yaml -o ${WORK}/diagnosis.html)
expect_in(${WORK}/diagnosis.html "report diagnose"
  "id=\"diagnose-models\"" "id=\"diagnose-effects\"" "id=\"residual-x\"" "id=\"residual-t\""
  ">s_x (mm)</text>" ">t (s)</text>" ">residual (µm)</text>" "<td>ae-arm + effects</td>")
# With the tables' uncertainty (the machine file's `uncertainty`): the page
# says every u holds it and gives each effect's two parts.
run_ok("report diagnose --table-uncertainty" report diagnose
       --measured ${SRC}/machines/sample/measured-grid.csv
       --machine ${SRC}/machines/sample/machine-uncertainty.yaml --table-uncertainty 10
       -o ${WORK}/diagnosis-tables.html)
expect_in(${WORK}/diagnosis-tables.html "report diagnose --table-uncertainty"
  "the tables&#39; uncertainty, √(data² + tables²): 10 draws of the campaign"
  "u from the data and from the tables: value ")
# The plug plate in its own coordinates against the sample machine: the
# page warns that the points lie outside the travel.
execute_process(COMMAND ${ABBE} import plugplate ${SRC}/tests/data/plugplate/D8131_1
                        -o ${WORK}/plate-8131.csv RESULT_VARIABLE rc)
run_ok("report diagnose beyond the travel" report diagnose --measured ${WORK}/plate-8131.csv
       --machine ${SRC}/machines/sample/machine.yaml -o ${WORK}/diagnosis-travel.html)
expect_in(${WORK}/diagnosis-travel.html "report diagnose beyond the travel"
  "points outside the travel" "machine coordinates")

# ISO 230-2 report of the sample machine's runs: a chart per component.
run_ok("report iso230" report iso230 ${SRC}/machines/sample/runs.csv -o ${WORK}/iso230.html)
file(SHA256 ${SRC}/machines/sample/runs.csv runs_sha)
expect_in(${WORK}/iso230.html "report iso230"
  "id=\"iso230-table\"" "id=\"iso230-x-exx\"" "id=\"iso230-z-ezz\"" "<td>X</td><td>EXX</td>"
  ">target position X (mm)</text>" "x̄↑ ± 2s↑" "x̄↓ ± 2s↓" "${runs_sha}")
# The same from standard input; a runs file with one run per target: exit 1.
execute_process(COMMAND ${ABBE} report iso230 - -o -
                INPUT_FILE ${SRC}/tests/data/iso230/hand.csv OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT out MATCHES "id=\"iso230-x-exx\".*</html>\n$")
  message(FATAL_ERROR "report iso230 - -o -: exit ${rc}")
endif()
execute_process(COMMAND ${ABBE} report iso230 ${SRC}/tests/data/iso230/one-run.csv
                        -o ${WORK}/keep-iso.html RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "one-run.csv" OR EXISTS ${WORK}/keep-iso.html)
  message(FATAL_ERROR "report iso230 one-run.csv: exit ${rc}\n${err}")
endif()

# Bad input: exit 1, file and line named, an existing output left alone.
file(WRITE ${WORK}/bad.ngc "G0 X0\nG1 X10 Q7 F100\n")
file(WRITE ${WORK}/keep.html "previous\n")
execute_process(COMMAND ${ABBE} report predict ${WORK}/bad.ngc --machine ${MACHINE}
                        -o ${WORK}/keep.html
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "bad.ngc:2:")
  message(FATAL_ERROR "bad program: exit ${rc}\n${err}")
endif()
file(READ ${WORK}/keep.html keep)
if(NOT keep STREQUAL "previous\n")
  message(FATAL_ERROR "bad program: the output was changed")
endif()
execute_process(COMMAND ${ABBE} report predict ${WORK}/missing.ngc --machine ${MACHINE}
                        -o ${WORK}/keep.html RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "missing.ngc")
  message(FATAL_ERROR "missing program: exit ${rc}\n${err}")
endif()
# Usage errors: exit 2.
execute_process(COMMAND ${ABBE} report predict ${WORK}/bad.ngc RESULT_VARIABLE rc
                ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "missing --machine: exit ${rc}, expected 2")
endif()
