# Command-level tests of `abbe compensate` and `abbe verify`. Included from
# tests/CMakeLists.txt; the file-system cases run in script mode (cmake -P).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_compensate cli_compensate_work "cli;compensate")
  # A generated program of 4 000 blocks (arcs in all planes, helices,
  # corners): compensated within tol at every point, forward and backward.
  add_script_test(cli_compensate_generated cli_compensate_generated_work "cli;compensate"
                  DEFINES -DGEN=$<TARGET_FILE:gen_program>)
  return()
endif()

include(${SRC}/tests/cli/lib/compensate_script.cmake)

if(GEN)
  run(0 ${GEN} --blocks 4000 --seed 11 -o ${WORK}/gen.ngc)
  run(0 ${ABBE} compensate ${WORK}/gen.ngc --machine ${MACHINE} -o ${WORK}/gen-c.ngc)
  run(0 ${ABBE} verify ${WORK}/gen-c.ngc --against ${WORK}/gen.ngc --machine ${MACHINE} --check)
  if(NOT OUT MATCHES " 0 beyond tol\n.* 0 beyond tol\n.*: pass")
    message(FATAL_ERROR "verify of the generated program: ${OUT}")
  endif()
  return()
endif()

# Every sample: compensate, then verify --check at 1 µm.
foreach(f thesis-toolpath-1 thesis-toolpath-2 spline-slot spline-slot-corner inch-r-arcs
          helix-g18-g19 drilling)
  run(0 ${ABBE} compensate ${SRC}/nc-samples/${f}.ngc --machine ${MACHINE} -o ${WORK}/${f}.ngc)
  if(NOT OUT MATCHES "blocks changed, [0-9]+ pieces inserted, [0-9]+ points, max correction [0-9.]+ µm, [0-9]+ out of range \\(clamp\\), 0 unconverged")
    message(FATAL_ERROR "summary of ${f}: ${OUT}")
  endif()
  run(0 ${ABBE} verify ${WORK}/${f}.ngc --against ${SRC}/nc-samples/${f}.ngc --machine ${MACHINE}
      --tol 1 --check)
  if(NOT OUT MATCHES " 0 beyond tol\n.* 0 beyond tol\n.*: pass")
    message(FATAL_ERROR "verify of ${f}: ${OUT}")
  endif()
  # All-zero tables: byte for byte after the provenance block (its lines
  # start with "(abbe"; a "%" first line stays first).
  run(0 ${ABBE} compensate ${SRC}/nc-samples/${f}.ngc --machine ${ZERO} -o ${WORK}/${f}-zero.ngc)
  file(READ ${SRC}/nc-samples/${f}.ngc original)
  file(READ ${WORK}/${f}-zero.ngc zero)
  string(REGEX REPLACE "\\(abbe[^\n]*\n" "" zero "${zero}")
  if(NOT original STREQUAL zero)
    message(FATAL_ERROR "${f}: zero tables changed the program")
  endif()
endforeach()

# verify --check fails on the uncompensated program: exit 4 (a check failed).
run(4 ${ABBE} verify ${SRC}/nc-samples/thesis-toolpath-1.ngc
    --against ${SRC}/nc-samples/thesis-toolpath-1.ngc --machine ${MACHINE} --check)

# A program the front end refuses: the same message, exit 1, no output.
file(WRITE ${WORK}/bad.nc "G21 G90\nG1 X-10 Y-10 Z-10 F100\nG2 X-20 Y-5\n")
run(1 ${ABBE} interpret ${WORK}/bad.nc)
set(front "${OUT}")
run(1 ${ABBE} compensate ${WORK}/bad.nc --machine ${MACHINE} -o ${WORK}/bad-out.nc)
string(FIND "${OUT}" "bad.nc:3:" pos)
if(pos LESS 0 OR EXISTS ${WORK}/bad-out.nc)
  message(FATAL_ERROR "bad program: ${OUT}")
endif()

# The input is never the output without --in-place.
file(COPY ${SRC}/nc-samples/thesis-toolpath-1.ngc DESTINATION ${WORK}/inplace)
file(SHA256 ${WORK}/inplace/thesis-toolpath-1.ngc before)
run(1 ${ABBE} compensate ${WORK}/inplace/thesis-toolpath-1.ngc --machine ${MACHINE}
    -o ${WORK}/inplace/thesis-toolpath-1.ngc)
file(SHA256 ${WORK}/inplace/thesis-toolpath-1.ngc after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "the input was overwritten without --in-place")
endif()
run(0 ${ABBE} compensate ${WORK}/inplace/thesis-toolpath-1.ngc --machine ${MACHINE} --in-place)
file(SHA256 ${WORK}/inplace/thesis-toolpath-1.ngc after)
if(before STREQUAL after)
  message(FATAL_ERROR "--in-place did not rewrite the input")
endif()

# A read-only output directory: exit 1, nothing left behind, input untouched.
file(MAKE_DIRECTORY ${WORK}/ro)
file(COPY ${SRC}/nc-samples/spline-slot.ngc DESTINATION ${WORK}/ro)
file(SHA256 ${WORK}/ro/spline-slot.ngc before)
execute_process(COMMAND chmod a-w ${WORK}/ro)
execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(uid STREQUAL "0" AND IS_DIRECTORY /sys)  # root writes anywhere but in a read-only file system
  run(1 ${ABBE} compensate ${WORK}/ro/spline-slot.ngc --machine ${MACHINE} -o /sys/abbe-out.ngc)
  if(NOT OUT MATCHES "/sys/abbe-out.ngc")
    message(FATAL_ERROR "read-only location: ${OUT}")
  endif()
elseif(NOT uid STREQUAL "0")
  run(1 ${ABBE} compensate ${WORK}/ro/spline-slot.ngc --machine ${MACHINE} -o ${WORK}/ro/out.ngc)
  file(GLOB left ${WORK}/ro/*)
  list(LENGTH left n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "read-only directory: files left ${left}")
  endif()
endif()
file(SHA256 ${WORK}/ro/spline-slot.ngc after)
execute_process(COMMAND chmod u+w ${WORK}/ro)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "read-only case touched the input")
endif()

# A full device: the write fails with exit 1.
if(EXISTS /dev/full)
  run(1 ${ABBE} compensate ${SRC}/nc-samples/spline-slot.ngc --machine ${MACHINE} -o /dev/full)
endif()
