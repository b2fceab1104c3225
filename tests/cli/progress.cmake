# Progress bars on stderr (docs/getting-started.md): drawn when stderr is a
# terminal (a pseudo-terminal from util-linux `script`), absent when stderr
# is redirected and with -q. Script mode (cmake -P).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_progress
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_progress_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_progress PROPERTIES LABELS cli)
  return()
endif()
include(${CMAKE_CURRENT_LIST_DIR}/lib/script_helpers.cmake)

find_program(SCRIPT script REQUIRED)  # util-linux (bsdutils)
set(MACHINE ${SRC}/machines/sample/machine.yaml)
set(PROGRAM ${SRC}/nc-samples/spline-slot.ngc)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# on_tty(NAME COMMAND): runs the command with stdin/stdout/stderr on a
# pseudo-terminal; its terminal output in tty_out.
function(on_tty name)
  string(JOIN " " cmd ${ARGN})
  execute_process(COMMAND ${SCRIPT} -qfec "${cmd}" /dev/null RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} on a terminal: exit ${rc}\n${out}\n${err}")
  endif()
  set(tty_out "${out}" PARENT_SCOPE)
endfunction()

# bar_test(NAME BAR_REGEX COMMAND…)
function(bar_test name regex)
  on_tty(${name} ${ARGN})
  if(NOT tty_out MATCHES "${regex}")
    message(FATAL_ERROR "${name}: no progress bar on the terminal:\n${tty_out}")
  endif()
  # -q: no bar even on a terminal.
  list(GET ARGN 0 exe)
  list(SUBLIST ARGN 1 -1 rest)
  on_tty(${name}-q ${exe} -q ${rest})
  if(tty_out MATCHES "${regex}")
    message(FATAL_ERROR "${name} -q: a progress bar was drawn:\n${tty_out}")
  endif()
  # stderr redirected to a file: silent.
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exit ${rc}\n${err}")
  endif()
  if("${out}${err}" MATCHES "${regex}" OR "${err}" MATCHES "\r")
    message(FATAL_ERROR "${name}: progress output when stderr is not a terminal:\n${err}")
  endif()
endfunction()

bar_test(compensate "compensate: \\[[#.]+\\] +[0-9]+%"
         ${ABBE} compensate ${PROGRAM} --machine ${MACHINE} -o ${WORK}/c.ngc)
bar_test(verify "verify: \\[[#.]+\\] +[0-9]+%"
         ${ABBE} verify ${WORK}/c.ngc --against ${PROGRAM} --machine ${MACHINE})
bar_test(map "map: \\[[#.]+\\] +[0-9]+% [0-9]+/[0-9]+ points"
         ${ABBE} map --machine ${MACHINE} --grid 40 --model ae-arm)
bar_test(diagnose "diagnose: \\[[#.]+\\] +[0-9]+%"
         ${ABBE} diagnose --machine ${MACHINE} --measured ${SRC}/machines/sample/measured-grid.csv)
