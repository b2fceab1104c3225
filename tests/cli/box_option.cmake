# --box takes one form in `abbe map` and `abbe simulate measure`: the two
# corners x0,y0,z0,x1,y1,z1 (lowest first); both give the same grid for the
# same box, and min/max pairs are refused with a message saying so.
# Script mode (cmake -P).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_box_option
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_box_option_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_box_option PROPERTIES LABELS cli)
  return()
endif()
include(${CMAKE_CURRENT_LIST_DIR}/lib/script_helpers.cmake)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(BOX -600,-300,-400,-400,-200,-300)  # x -600…-400, y -300…-200, z -400…-300

run(${ABBE} map --machine ${SRC}/machines/sample/machine.yaml --box ${BOX} --grid 100
    --model ae-arm -o ${WORK}/map.csv)
if(NOT run_out MATCHES "3 × 2 × 2 = 12 grid points, box \\(-600, -300, -400\\) – \\(-400, -200, -300\\)")
  message(FATAL_ERROR "map --box: ${run_out}")
endif()
run(${ABBE} simulate measure --truth ${SRC}/machines/sample/truth.yaml --box ${BOX} --grid 100
    --noise 0um -o ${WORK}/measured.csv)
file(STRINGS ${WORK}/measured.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 13)  # header + the same 12 points
  message(FATAL_ERROR "simulate measure --box: ${n} lines, expected 13")
endif()
# Every measured point lies in the box (x, y, z are the first three columns).
list(REMOVE_AT rows 0)
foreach(r ${rows})
  string(REPLACE "," ";" f "${r}")
  list(GET f 0 x)
  list(GET f 1 y)
  list(GET f 2 z)
  if(x LESS -600 OR x GREATER -400 OR y LESS -300 OR y GREATER -200 OR z LESS -400
     OR z GREATER -300)
    message(FATAL_ERROR "simulate measure --box: point ${x},${y},${z} outside the box")
  endif()
endforeach()

# The min/max form (x0,x1,y0,y1,z0,z1) is refused by both, naming the form.
foreach(cmd "map;--machine;${SRC}/machines/sample/machine.yaml"
            "simulate;measure;--truth;${SRC}/machines/sample/truth.yaml;-o;${WORK}/m2.csv")
  expect_failure("--box takes the two corners x0,y0,z0,x1,y1,z1" ${ABBE} ${cmd}
                 --box -800,-200,-400,-100,-500,-200 --grid 100)
endforeach()
