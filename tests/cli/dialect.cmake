# Command-level tests of --dialect fanuc: a Fanuc-style program and its
# hand translation into RS274/NGC make the same canonical motions, are
# compensated into the same motions, and a subprogram call runs like its
# written-out passes. Included from tests/CMakeLists.txt; runs in script mode.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_dialect_fanuc
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_dialect_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_dialect_fanuc PROPERTIES LABELS "cli;dialect")
  return()
endif()

include(${SRC}/tests/cli/lib/script_helpers.cmake)
set(MACHINE ${SRC}/machines/sample/machine.yaml)
set(DATA ${SRC}/tests/data/dialect)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_same_canon what a b)
  string(REGEX REPLACE "N[0-9]+ " "" a_motions "${a}")
  string(REGEX REPLACE "N[0-9]+ " "" b_motions "${b}")
  if(NOT a_motions STREQUAL b_motions)
    message(FATAL_ERROR "${what}: canonical motions differ\n--- a\n${a}\n--- b\n${b}")
  endif()
  string(REGEX MATCHALL "\n" lines "${a}")
  list(LENGTH lines n)
  if(n LESS 5)
    message(FATAL_ERROR "${what}: too few motions (${n}):\n${a}")
  endif()
endfunction()

# 1. The Fanuc program reads like its translation, motion for motion.
run(${ABBE} interpret ${DATA}/fanuc-pocket.nc --dialect fanuc --machine ${MACHINE} --canon)
set(fanuc "${run_out}")
run(${ABBE} interpret ${DATA}/fanuc-pocket-linuxcnc.ngc --machine ${MACHINE} --canon)
expect_same_canon("fanuc-pocket" "${fanuc}" "${run_out}")
# Without the dialect the file is read as RS274/NGC: integers are
# millimetres and G05.1 is refused by name, so it cannot make the same path.
execute_process(COMMAND ${ABBE} interpret ${DATA}/fanuc-pocket.nc --machine ${MACHINE} --canon
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 AND out STREQUAL fanuc)
  message(FATAL_ERROR "--dialect fanuc changed nothing")
endif()
if(NOT rc EQUAL 0 AND NOT err MATCHES "G5.1")
  message(FATAL_ERROR "without --dialect: exit ${rc}, not the named G5.1 refusal:\n${err}")
endif()

# 2. Compensated, both make the same motions: every number written into the
# Fanuc program carries a decimal point (an "X5" would be 0.005 mm there).
run(${ABBE} compensate ${DATA}/fanuc-pocket.nc --dialect fanuc --machine ${MACHINE}
    -o ${WORK}/fanuc-c.nc)
run(${ABBE} compensate ${DATA}/fanuc-pocket-linuxcnc.ngc --machine ${MACHINE}
    -o ${WORK}/linuxcnc-c.ngc)
run(${ABBE} interpret ${WORK}/fanuc-c.nc --dialect fanuc --machine ${MACHINE} --canon)
set(fanuc_c "${run_out}")
run(${ABBE} interpret ${WORK}/linuxcnc-c.ngc --machine ${MACHINE} --canon)
expect_same_canon("compensated fanuc-pocket" "${fanuc_c}" "${run_out}")
if(fanuc_c STREQUAL fanuc)
  message(FATAL_ERROR "compensation changed no motion of fanuc-pocket")
endif()
run(${ABBE} verify ${WORK}/fanuc-c.nc --against ${DATA}/fanuc-pocket.nc --dialect fanuc
    --machine ${MACHINE} --tol 1 --check)

# 3. Subprogram passes.
run(${ABBE} interpret ${DATA}/fanuc-subprogram.nc --dialect fanuc --machine ${MACHINE} --canon)
set(sub "${run_out}")
run(${ABBE} interpret ${DATA}/fanuc-subprogram-expanded.ngc --machine ${MACHINE} --canon)
expect_same_canon("fanuc-subprogram" "${sub}" "${run_out}")
expect_failure("subprogram calls (M98) are not compensated"
               ${ABBE} compensate ${DATA}/fanuc-subprogram.nc --dialect fanuc --machine ${MACHINE}
               -o ${WORK}/sub-c.nc)
# An unknown dialect is a usage error (exit 2) naming the option.
execute_process(COMMAND ${ABBE} path ${DATA}/fanuc-pocket.nc --dialect fanucc
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--dialect")
  message(FATAL_ERROR "--dialect fanucc: exit ${rc}\n${err}")
endif()
