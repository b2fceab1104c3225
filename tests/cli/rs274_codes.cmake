# Command-level tests of the codes posts emit (G28/G30, G10, G52, G93/G95,
# G84/G74/G86) and of the defaults a newcomer meets (G43 H without a tool
# table, rotary words that never move, a second '%'), against canonical
# motions worked out by hand (tests/data/rs274/*.canon), and of the
# front-end limits (a line without end, a move needing absurd point counts,
# LinuxCNC's full-circle rule for tiny sweeps). Runs in script mode.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_rs274_codes
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_rs274_codes_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_rs274_codes PROPERTIES LABELS "cli")
  return()
endif()

include(${SRC}/tests/cli/lib/script_helpers.cmake)
set(DATA ${SRC}/tests/data/rs274)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_canon name)
  run(${ABBE} interpret ${DATA}/${name}.ngc --canon ${ARGN})
  file(READ ${DATA}/${name}.canon expected)
  if(NOT run_out STREQUAL expected)
    message(FATAL_ERROR "${name}: canonical motions differ\n--- abbe\n${run_out}\n--- expected\n${expected}")
  endif()
endfunction()

expect_canon(home)
expect_canon(offsets)
expect_canon(cycles)
expect_canon(newcomer)

# The stored G28/G30 positions come from the machine file (home_positions).
file(READ ${SRC}/machines/sample/machine.yaml yaml)
string(REPLACE "table: errors.csv" "table: ${SRC}/machines/sample/errors.csv" yaml
               "${yaml}")
string(REGEX REPLACE "\nsquareness:" "\nhome_positions:\n  G28: [-100, -50, -20]\n  G30: [-1, -2, -3]\nsquareness:"
                     yaml "${yaml}")
file(WRITE ${WORK}/machine.yaml "${yaml}")
file(WRITE ${WORK}/g28.ngc "G21 G90\nG0 X1 Y2 Z-200\nG28\nG30 Y0\nM2\n")
run(${ABBE} interpret ${WORK}/g28.ngc --canon --machine ${WORK}/machine.yaml)
# The sample machine's tool (130 mm, no G43: the program drives the spindle
# nose) hangs below the stored spindle position.
set(expected "N2 STRAIGHT_TRAVERSE(1.000000, 2.000000, -330.000000) F=0.000000 TL=130.000000
N3 STRAIGHT_TRAVERSE(1.000000, 2.000000, -330.000000) F=0.000000 TL=130.000000
N3 STRAIGHT_TRAVERSE(-100.000000, -50.000000, -150.000000) F=0.000000 TL=130.000000
N4 STRAIGHT_TRAVERSE(-100.000000, 0.000000, -150.000000) F=0.000000 TL=130.000000
N4 STRAIGHT_TRAVERSE(-100.000000, -2.000000, -150.000000) F=0.000000 TL=130.000000
")
if(NOT run_out STREQUAL expected)
  message(FATAL_ERROR "home_positions: got\n${run_out}\nexpected\n${expected}")
endif()

# G43 H without a tool table: path and interpret go on (tool_length unknown),
# predict still needs the length.
run(${ABBE} path ${DATA}/newcomer.ngc --step 100)
string(FIND "${run_out}" ",unknown," at)
if(at EQUAL -1)
  message(FATAL_ERROR "path: no unknown tool_length in\n${run_out}")
endif()
expect_failure("tool 7 has no length in the tool table (G43 H7)"
               ${ABBE} predict ${DATA}/newcomer.ngc --machine ${SRC}/machines/sample/machine.yaml)

# A rotary axis that moves stays refused by name.
file(WRITE ${WORK}/rotary.ngc "G21\nG0 X0 A0\nG0 A90\n")
expect_failure("rotary.ngc:3:4: error: rotary axis A moves" ${ABBE} path ${WORK}/rotary.ngc)

# A file without line ends is refused at 16 MiB, not buffered without end.
string(REPEAT "(cccccccccccccc)" 1100000 long_line)
file(WRITE ${WORK}/no-newline.ngc "${long_line}")
expect_failure("no-newline.ngc:1: error: line reaches 16777216 bytes without a line end"
               ${ABBE} path ${WORK}/no-newline.ngc)

# A move needing more than 1e9 points is bad input at its line (exit 1).
file(WRITE ${WORK}/far.ngc "G21 F100\nG0 X0\nG1 X900000\n")
expect_failure("far.ngc:3:4: error: the linear motion of 900000 mm needs more than 1e9 points"
               ${ABBE} path ${WORK}/far.ngc --step 0.0001)

# A sweep below LinuxCNC's 1e-6 rad is a full circle (about 63 points at
# step 1 mm on radius 10), a sweep above it a short arc (one point).
file(WRITE ${WORK}/tiny-sweep.ngc "G21 F100\nG0 X10 Y0\nG3 X10 Y0.000001 I-10 J0\nM2\n")
run(${ABBE} path ${WORK}/tiny-sweep.ngc --step 1)
string(REGEX MATCHALL "\n" rows "${run_out}")
list(LENGTH rows n)
if(n LESS 60)
  message(FATAL_ERROR "tiny sweep: ${n} rows, expected a full circle\n${run_out}")
endif()
file(WRITE ${WORK}/short-arc.ngc "G21 F100\nG0 X10 Y0\nG3 X10 Y0.0001 I-10 J0\nM2\n")
run(${ABBE} path ${WORK}/short-arc.ngc --step 1)
string(REGEX MATCHALL "\n" rows "${run_out}")
list(LENGTH rows n)
# header, the rapid's 11 points (X0..X10 at step 1 mm), the arc's end: 13
if(NOT n EQUAL 13)
  message(FATAL_ERROR "short arc (1e-5 rad): ${n} rows, expected 13\n${run_out}")
endif()
