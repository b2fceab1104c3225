# Real Fanuc/Haas-style programs written by CAM posts (tests/data/fanuc,
# sources in its README): every one through `abbe path --dialect fanuc` is
# accepted or refused by a named construct, as tests/data/fanuc/expected.txt
# says; the first motions of three of them are checked against values worked
# out by hand from the program text. Runs in script mode.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_fanuc_corpus
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_fanuc_corpus PROPERTIES LABELS "cli;dialect")
  return()
endif()

set(DATA ${SRC}/tests/data/fanuc)
file(STRINGS ${DATA}/expected.txt cases REGEX "^[^#]")
list(LENGTH cases n)
if(n LESS 20)
  message(FATAL_ERROR "fanuc corpus: only ${n} programs in expected.txt")
endif()
set(n_accepted 0)
set(n_refused 0)
foreach(line ${cases})
  string(REPLACE "|" ";" fields "${line}")
  list(GET fields 0 file)
  list(GET fields 1 outcome)
  execute_process(COMMAND ${ABBE} path ${DATA}/${file} --dialect fanuc --count
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(outcome STREQUAL "accepted")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${file}: expected to be accepted, exit ${rc}\n${err}")
    endif()
    math(EXPR n_accepted "${n_accepted} + 1")
  else()
    list(GET fields 2 message)
    string(FIND "${err}" "${message}" at)
    if(NOT rc EQUAL 1 OR at EQUAL -1)
      message(FATAL_ERROR "${file}: expected exit 1 with '${message}', exit ${rc}\n${err}")
    endif()
    math(EXPR n_refused "${n_refused} + 1")
  endif()
endforeach()
message(STATUS "fanuc corpus: ${n_accepted} accepted, ${n_refused} refused by name")

# With the cutter's diameter (tool 2, a 1/2 in end mill) the SOLIDWORKS CAM
# contours get past G41 D002 and stop at rs274ngc's rule for the entry move:
# their entry moves (0.0002 and 0.3) are shorter than the tool radius.
file(GLOB solidworks RELATIVE ${DATA} ${DATA}/nick-burrill-solidworks-*.nc)
foreach(file ${solidworks})
  execute_process(COMMAND ${ABBE} path ${DATA}/${file} --dialect fanuc --count
                          --tool-diameter 2=12.7
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${err}" "cutter radius compensation: the entry move" at)
  if(NOT rc EQUAL 1 OR at EQUAL -1)
    message(FATAL_ERROR "${file} with --tool-diameter 2=12.7: expected the entry move "
                        "refusal, exit ${rc}\n${err}")
  endif()
endforeach()

# Hand checks: the first motions (tool tip, machine coordinates, mm; no
# machine file: G54 = 0, stored G28 position = 0, tools without a length).
function(expect_first file expected)
  execute_process(COMMAND ${ABBE} interpret ${DATA}/${file} --dialect fanuc --canon
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(LENGTH "${expected}" len)
  string(SUBSTRING "${out}" 0 ${len} head)
  if(NOT head STREQUAL expected)
    message(FATAL_ERROR "${file}: first motions differ\n--- abbe\n${head}\n--- by hand\n${expected}")
  endif()
endfunction()

# N20 G28 G91 Z0. (intermediate point, then Z home), N55 G0 X-45. Y41.5,
# N60 G43 Z15. H1, N65 Z5., N70 G1 Z1. F50., N75 Z-2., N80 X 45. F300.,
# N85 G2 X51.613 Y38.605 I0. J-9. (centre 45, 32.5).
expect_first(fgodoy27-1001.nc
"N5 STRAIGHT_TRAVERSE(0.000000, 0.000000, 0.000000) F=0.000000 TL=0.000000
N5 STRAIGHT_TRAVERSE(0.000000, 0.000000, 0.000000) F=0.000000 TL=0.000000
N12 STRAIGHT_TRAVERSE(-45.000000, 41.500000, 0.000000) F=0.000000 TL=0.000000
N13 STRAIGHT_TRAVERSE(-45.000000, 41.500000, 15.000000) F=0.000000 TL=nan
N14 STRAIGHT_TRAVERSE(-45.000000, 41.500000, 5.000000) F=0.000000 TL=nan
N15 STRAIGHT_FEED(-45.000000, 41.500000, 1.000000) F=50.000000 TL=nan
N16 STRAIGHT_FEED(-45.000000, 41.500000, -2.000000) F=50.000000 TL=nan
N17 STRAIGHT_FEED(45.000000, 41.500000, -2.000000) F=300.000000 TL=nan
N18 ARC_FEED(51.613000, 38.605000, 45.000000, 32.500000, -1, -2.000000) PLANE=XY F=300.000000 TL=nan
")

# Inch program: G28 G91 Z0., T2 M06, G00 X2.7396 Y-1.32, G43 Z0.6 H02,
# G00 Z0.2, G01 Z-0.006 F3.3, Y-1.0966 F10. (× 25.4).
expect_first(rawdograps-1401.nc
"N15 STRAIGHT_TRAVERSE(0.000000, 0.000000, 0.000000) F=0.000000 TL=0.000000
N15 STRAIGHT_TRAVERSE(0.000000, 0.000000, 0.000000) F=0.000000 TL=0.000000
N25 STRAIGHT_TRAVERSE(69.585840, -33.528000, 0.000000) F=0.000000 TL=0.000000
N26 STRAIGHT_TRAVERSE(69.585840, -33.528000, 15.240000) F=0.000000 TL=nan
N27 STRAIGHT_TRAVERSE(69.585840, -33.528000, 5.080000) F=0.000000 TL=nan
N28 STRAIGHT_FEED(69.585840, -33.528000, -0.152400) F=83.820000 TL=nan
N29 STRAIGHT_FEED(69.585840, -27.853640, -0.152400) F=254.000000 TL=nan
")

# A G98 G81 drilling cycle from the initial level 0.1969 in to R 0.1575 in
# and Z-0.2072 in at F53.2 in/min, back to the initial level.
expect_first(nick-burrill-fusion360-drill-tap.nc
"N36 STRAIGHT_TRAVERSE(0.000000, 0.000000, 0.000000) F=0.000000 TL=0.000000
N36 STRAIGHT_TRAVERSE(0.000000, 0.000000, 0.000000) F=0.000000 TL=0.000000
N44 STRAIGHT_TRAVERSE(204.000100, -199.999600, 0.000000) F=0.000000 TL=0.000000
N45 STRAIGHT_TRAVERSE(204.000100, -199.999600, 15.001240) F=0.000000 TL=nan
N46 STRAIGHT_TRAVERSE(204.000100, -199.999600, 5.001260) F=0.000000 TL=nan
N47 STRAIGHT_TRAVERSE(204.000100, -199.999600, 5.001260) F=0.000000 TL=nan
N47 STRAIGHT_TRAVERSE(204.000100, -199.999600, 4.000500) F=0.000000 TL=nan
N47 STRAIGHT_FEED(204.000100, -199.999600, -5.262880) F=1351.280000 TL=nan
N47 STRAIGHT_TRAVERSE(204.000100, -199.999600, 5.001260) F=0.000000 TL=nan
")
