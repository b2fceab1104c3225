# The start of the script mode of the compensation tests (compensate.cmake,
# export.cmake): the sample machine in MACHINE, the zero-error machine in
# ZERO, an empty WORK, and run()/expect() of exit_code_helpers.cmake.
set(MACHINE ${SRC}/machines/sample/machine.yaml)
set(ZERO ${SRC}/tests/data/compensate/zero.yaml)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/exit_code_helpers.cmake)
