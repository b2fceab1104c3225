# The installed library (docs/library.md): `cmake --install` of this build
# tree into a scratch prefix, then tests/consumer/ (a project of its own)
# is configured with find_package(abbe), built and run, and built once more
# with pkg-config alone. Its |e| at one point must equal the one `abbe predict`
# gives for the same point from a CSV of points.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME consumer_project
           COMMAND ${CMAKE_COMMAND} -DBUILD=${CMAKE_BINARY_DIR} -DROOT=${PROJECT_SOURCE_DIR}
                   -DABBE=$<TARGET_FILE:abbe> -DCXX=${CMAKE_CXX_COMPILER}
                   -DGENERATOR=${CMAKE_GENERATOR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/consumer_work -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(consumer_project PROPERTIES LABELS "cli;consumer" TIMEOUT 600)
  return()
endif()

include(${CMAKE_CURRENT_LIST_DIR}/lib/script_helpers.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(prefix ${WORK}/prefix)
set(machine ${ROOT}/machines/sample/machine.yaml)

run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(f bin/abbe include/abbe/pipeline/predict.hpp include/abbe/io/input_error.hpp)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "cmake --install did not install ${f}")
  endif()
endforeach()
file(GLOB_RECURSE config ${prefix}/*/abbeConfig.cmake)
file(GLOB_RECURSE pc ${prefix}/*/abbe.pc)
if(NOT config OR NOT pc)
  message(FATAL_ERROR "no abbeConfig.cmake or abbe.pc under ${prefix}")
endif()

# The reference: abbe predict on one point of a CSV.
file(WRITE ${WORK}/point.csv "x,y,z\n-300,-200,-150\n")
run(${prefix}/bin/abbe predict ${WORK}/point.csv --machine ${machine} --model ae-arm -o -)
string(REGEX MATCH "\n[^\n]+" row "${run_out}")
string(REPLACE "," ";" row "${row}")
list(GET row 9 expected)

function(check_consumer exe)
  run(${exe} ${machine} -300 -200 -150)
  if(NOT run_out MATCHES "consumer: \\|e\\| = ([0-9.e+-]+) µm")
    message(FATAL_ERROR "unexpected consumer output: ${run_out}")
  endif()
  set(got ${CMAKE_MATCH_1})
  execute_process(COMMAND python3 -c "import sys; sys.exit(abs(${got}-${expected}) > 1e-3)"
                  RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${exe}: |e| = ${got} µm, abbe predict says ${expected} µm")
  endif()
  message(STATUS "${exe}: |e| = ${got} µm (abbe predict: ${expected} µm)")
endfunction()

# 1. CMake: find_package(abbe) -> abbe::core.
run(${CMAKE_COMMAND} -S ${ROOT}/tests/consumer -B ${WORK}/build -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK}/build)
check_consumer(${WORK}/build/consumer)

# 2. pkg-config alone.
get_filename_component(pcdir ${pc} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pcdir})
run(pkg-config --cflags --libs abbe)
string(STRIP "${run_out}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${CXX} -std=c++17 ${ROOT}/tests/consumer/main.cpp -o ${WORK}/consumer_pc ${flags})
check_consumer(${WORK}/consumer_pc)
