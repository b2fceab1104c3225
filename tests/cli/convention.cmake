# The CLI convention (README, tools/abbe/output_options.hpp): global options
# anywhere, -o - with the summary on stderr, - as input, exit code 4 for a
# failed check, an example in every --help, CSV as spreadsheets save it.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_convention cli_convention cli TIMEOUT 600)
  return()
endif()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(machine ${SRC}/machines/sample/machine.yaml)
set(program ${SRC}/nc-samples/thesis-toolpath-1.ngc)

include(${SRC}/tests/cli/lib/exit_code_helpers.cmake)
# run_stdin(<expected exit> <stdin file> <args...>)
function(run_stdin expect input)
  execute_process(COMMAND ${ARGN} INPUT_FILE ${input} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL expect)
    message(FATAL_ERROR "expected exit ${expect}, got ${rc}: ${ARGN} < ${input}\n${out}\n${err}")
  endif()
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
endfunction()

# Global options anywhere on the line.
run_apart(0 ${ABBE} -q path ${program} --tool 1=200 --count)
run_apart(0 ${ABBE} path ${program} --tool 1=200 --count -q)
run_apart(0 ${ABBE} path -v ${program} --tool 1=200 --count)
run_apart(0 ${ABBE} simulate measure --truth ${SRC}/machines/sample/truth.yaml --grid 400 -q -o -)

# -o -: the data alone on stdout, the summary on stderr.
run_apart(0 ${ABBE} map --machine ${machine} --grid 200 -o -)
if(NOT OUT MATCHES "^x,y,z," OR OUT MATCHES "grid points")
  message(FATAL_ERROR "map -o -: stdout is not the CSV alone:\n${OUT}")
endif()
if(NOT ERR MATCHES "grid points")
  message(FATAL_ERROR "map -o -: no summary on stderr:\n${ERR}")
endif()
run_apart(0 ${ABBE} map --machine ${machine} --grid 200 -o ${WORK}/map.csv)
if(NOT OUT MATCHES "grid points")
  message(FATAL_ERROR "map -o FILE: no summary on stdout:\n${OUT}")
endif()

# - as input: the same bytes as from the file. The provenance block carries
# the date to the second: fix it, or two runs straddling a second differ.
set(ENV{SOURCE_DATE_EPOCH} 1764115200)
run_apart(0 ${ABBE} compensate ${program} --machine ${machine} -o -)
set(from_file "${OUT}")
run_stdin(0 ${program} ${ABBE} compensate - --machine ${machine} -o -)
if(NOT OUT STREQUAL from_file)
  message(FATAL_ERROR "compensate - differs from compensate FILE")
endif()
file(WRITE ${WORK}/comp.ngc "${OUT}")
run_stdin(0 ${WORK}/comp.ngc ${ABBE} verify - --against ${program} --machine ${machine} --check)
run_apart(1 ${ABBE} compensate - --machine ${machine} --in-place)

# diagnose: measured data from stdin, the JSON report on stdout, the summary
# on stderr; the old --out still works.
run_stdin(0 ${SRC}/machines/sample/measured-grid.csv
          ${ABBE} diagnose --machine ${machine} --measured - -o -)
if(NOT OUT MATCHES "^{" OR NOT ERR MATCHES "points")
  message(FATAL_ERROR "diagnose --measured - -o -: unexpected streams:\n${OUT}\n---\n${ERR}")
endif()
run_apart(0 ${ABBE} diagnose --machine ${machine} --measured ${SRC}/machines/sample/measured-grid.csv
    --out ${WORK}/diagnosis.json -q)
if(NOT EXISTS ${WORK}/diagnosis.json)
  message(FATAL_ERROR "diagnose --out (hidden alias) wrote nothing")
endif()

# A failed check: exit 4, not the 1 of bad input.
run_apart(4 ${ABBE} verify ${program} --against ${program} --machine ${machine} --check)

# An example in every --help (every command and subcommand).
foreach(cmd path interpret predict compensate verify "simulate machine" "simulate campaign"
        "simulate measure" "report predict" "report map" "report compensate" "report diagnose"
        "export linuxcnc" "export grid" map diagnose identify iso230 import)
  separate_arguments(words UNIX_COMMAND "${cmd}")
  run_apart(0 ${ABBE} ${words} --help)
  if(NOT OUT MATCHES "Example")
    message(FATAL_ERROR "abbe ${cmd} --help has no example:\n${OUT}")
  endif()
endforeach()

# CSV as spreadsheets save it: BOM + upper case + CRLF + quotes, and `;`
# with decimal commas, predict the same numbers as the plain file.
file(WRITE ${WORK}/plain.csv "x,y,z\n-300.5,-200,-150\n-100,-50.25,-20\n")
string(ASCII 239 187 191 bom)  # UTF-8 byte-order mark, as Excel writes it
file(WRITE ${WORK}/excel.csv "${bom}X,Y,Z\r\n\"-300.5\",-200,-150\r\n-100,\"-50.25\",-20\r\n")
file(WRITE ${WORK}/semicolon.csv "x;y;z\n-300,5;-200;-150\n-100;-50,25;-20\n")
run_apart(0 ${ABBE} predict ${WORK}/plain.csv --machine ${machine} -o -)
string(REGEX REPLACE "plain\\.csv" "" plain "${OUT}")
foreach(f excel semicolon)
  run_apart(0 ${ABBE} predict ${WORK}/${f}.csv --machine ${machine} -o -)
  if(NOT OUT STREQUAL plain)
    message(FATAL_ERROR "${f}.csv predicts differently:\n${OUT}\nplain:\n${plain}")
  endif()
endforeach()
# Errors keep file, line and column.
file(WRITE ${WORK}/bad.csv "X;Y;Z\n1;2;3\n1;\"2\";zz\n")
run_apart(1 ${ABBE} predict ${WORK}/bad.csv --machine ${machine})
if(NOT ERR MATCHES "bad\\.csv:3:7 \\[z\\]: error: \"zz\" is not a finite number")
  message(FATAL_ERROR "bad.csv: unexpected message:\n${ERR}")
endif()

# iso230: --format json (the old --json still works).
run_apart(0 ${ABBE} iso230 ${SRC}/machines/sample/runs.csv --format json)
set(json "${OUT}")
run_apart(0 ${ABBE} iso230 ${SRC}/machines/sample/runs.csv --json)
if(NOT OUT STREQUAL json OR NOT json MATCHES "^[[{]")
  message(FATAL_ERROR "iso230 --format json and --json differ")
endif()
file(REMOVE_RECURSE ${WORK})
