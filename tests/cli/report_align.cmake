# Command-level tests of `abbe report predict --align best-fit|datums
# [--uncertainty N]` (docs/report.md): the page shows the deviation after the
# part's set-up beside the absolute one, with the figures of `abbe predict
# --align`; the same usage errors as predict; a part that cannot be aligned
# is bad input and leaves the output untouched.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_report_align cli_report_align_work cli TIMEOUT 300)
  return()
endif()

# ---- script mode ----
include(${CMAKE_CURRENT_LIST_DIR}/lib/script_helpers.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/lib/refusal_helpers.cmake)
set(machine ${SRC}/tests/data/machines/sample.yaml)
set(umachine ${SRC}/machines/sample/machine-uncertainty.yaml)
set(program ${SRC}/nc-samples/thesis-toolpath-1.ngc)
start_with_previous_output(${WORK}/out.html)

# Best fit, every model: both plots per model and the part table.
run(${ABBE} report predict ${program} --machine ${machine} --model all --align best-fit
    -o ${WORK}/best-fit.html)
file(READ ${WORK}/best-fit.html html)
foreach(s "id=\"part-table\"" "id=\"deviation-ae-arm\"" "id=\"aligned-deviation-ae-arm\""
          "id=\"aligned-deviation-htm\"" "id=\"aligned-deviation-dual\""
          "Deviation after best-fit alignment, ae-arm model" "<td>after alignment</td>")
  string(FIND "${html}" "${s}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "report predict --align best-fit: '${s}' not found")
  endif()
endforeach()
# The aligned row of ae-arm has the figures of `abbe predict --align best-fit`.
run(${ABBE} predict ${program} --machine ${machine} --model ae-arm --align best-fit
    --summary-only)
if(NOT run_out MATCHES "ae-arm +absolute[^\n]*\n +aligned +([0-9.]+) +([0-9.]+) +([0-9.]+) +([0-9.]+) +([0-9.]+)\n")
  message(FATAL_ERROR "abbe predict --align summary:\n${run_out}")
endif()
set(rms ${CMAKE_MATCH_4})
set(maxd ${CMAKE_MATCH_5})
if(NOT html MATCHES "<td>ae-arm</td><td>after alignment</td><td>[0-9]+</td><td>[0-9.]+</td><td>[0-9.]+</td><td>[0-9.]+</td><td>([0-9.]+)</td><td>([0-9.]+)</td>")
  message(FATAL_ERROR "report predict --align best-fit: no aligned ae-arm row")
endif()
# The report writes 3 decimals, predict 4: they agree within the rounding.
foreach(pair "${CMAKE_MATCH_1};${rms}" "${CMAKE_MATCH_2};${maxd}")
  list(GET pair 0 a)
  list(GET pair 1 b)
  string(REPLACE "." "" a10 "${a}0")  # 10⁻⁴ µm
  string(REPLACE "." "" b10 "${b}")
  math(EXPR diff "${a10} - ${b10}")
  if(diff GREATER 5 OR diff LESS -5)
    message(FATAL_ERROR "aligned ae-arm figure: report ${a}, predict ${b}")
  endif()
endforeach()

# Datums (the rectangle's bottom, its first side, the corner after it).
run(${ABBE} report predict ${program} --machine ${machine} --model ae-arm --align datums
    --datum-primary 18-21 --datum-secondary 18 --datum-tertiary 19 -o ${WORK}/datums.html)
expect_file_matches(${WORK}/datums.html
  "datum \\(3-2-1\\) alignment from the primary \\([0-9]+ points\\).*id=\"aligned-deviation-ae-arm\""
  "report predict --align datums")

# With the draws: the bands of both plots and the aligned figures ± U.
run(${ABBE} report predict ${program} --machine ${umachine} --model ae-arm --align best-fit
    --uncertainty 10 --seed 3 -o ${WORK}/uncertain.html)
file(READ ${WORK}/uncertain.html html)
string(REGEX MATCHALL "<polygon class=\"band\"" bands "${html}")
list(LENGTH bands nbands)
if(NOT nbands EQUAL 6)
  message(FATAL_ERROR "report predict --align --uncertainty: ${nbands} bands, expected 6")
endif()
if(NOT html MATCHES "<td>ae-arm</td><td>after alignment</td><td>[0-9]+</td><td>[0-9.]+ ± [0-9.]+</td>")
  message(FATAL_ERROR "report predict --align --uncertainty: no aligned row with ± U")
endif()

# Usage errors (exit 2) and a part that cannot be aligned (exit 1): the
# output is left as it was.
function(expect code what pattern)
  refused_untouched(${code} "${what}" "${pattern}" ${WORK}/out.html
                    ${ABBE} report predict ${program} --machine ${machine} ${ARGN}
                    -o ${WORK}/out.html)
endfunction()
expect(2 "datums without sets" "abbe report predict: --align datums needs --datum-secondary"
       --align datums --datum-primary 18-21)
expect(2 "a datum set without --align datums"
       "abbe report predict: --datum-primary needs --align datums" --datum-primary 18-21)
expect(2 "unknown alignment" "--align" --align cmm)
expect(1 "empty tertiary datum" "thesis-toolpath-1.ngc.*tertiary datum needs at least 1"
       --align datums --datum-primary 18-21 --datum-secondary 18 --datum-tertiary 900)
expect(1 "bad line set" "\\[--datum-primary\\]: error: expected a line number"
       --align datums --datum-primary 18-x --datum-secondary 18 --datum-tertiary 19)
