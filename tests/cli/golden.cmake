# Golden outputs: the bytes that path, predict (one model, all models, JSON,
# a CSV of points), compensate, interpret and simulate measure write for every bundled
# NC sample, compared by SHA-256 with tests/data/golden/outputs.sha256. A
# refactoring must not change a byte; a deliberate change of an output is
# recorded with
#   cmake -DABBE=$PWD/build/test/abbe -DROOT=$PWD -DWORK=/tmp/golden -DUPDATE=ON \
#         -P tests/cli/golden.cmake
# and explained in the commit.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_golden_outputs
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DROOT=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_golden_work -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_golden_outputs PROPERTIES LABELS cli)
  return()
endif()

# Relative names: the outputs name their inputs, the same in every checkout.
# The date in the provenance block of compensated programs: fixed.
set(ENV{SOURCE_DATE_EPOCH} 0)
set(machine machines/sample/machine.yaml)
set(golden ${ROOT}/tests/data/golden/outputs.sha256)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

set(lines "")
function(run name)  # run(<output name> <abbe arguments...>): output to ${WORK}/<name>
  execute_process(COMMAND ${ABBE} ${ARGN} WORKING_DIRECTORY ${ROOT}
                  OUTPUT_FILE ${WORK}/${name}.stdout ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "abbe ${ARGN}: exit ${rc}\n${err}")
  endif()
  foreach(f ${name} ${name}.stdout)
    if(EXISTS ${WORK}/${f})
      file(SHA256 ${WORK}/${f} h)
      set(lines "${lines}${h}  ${f}\n" PARENT_SCOPE)
      set(lines "${lines}${h}  ${f}\n")
    endif()
  endforeach()
endfunction()

file(GLOB samples RELATIVE ${ROOT} ${ROOT}/nc-samples/*.ngc)
list(SORT samples)
foreach(s ${samples})
  get_filename_component(n ${s} NAME_WE)
  run(${n}.path.csv path ${s} --machine ${machine} -o ${WORK}/${n}.path.csv)
  run(${n}.path.json path ${s} --machine ${machine} --step 2 --format json -o ${WORK}/${n}.path.json)
  run(${n}.predict.csv predict ${s} --machine ${machine} -o ${WORK}/${n}.predict.csv)
  run(${n}.predict-all.csv predict ${s} --machine ${machine} --model all
      -o ${WORK}/${n}.predict-all.csv)
  run(${n}.predict-dual.json predict ${s} --machine ${machine} --model dual --format json
      -o ${WORK}/${n}.predict-dual.json --summary-json ${WORK}/${n}.summary.json)
  run(${n}.compensated.ngc compensate ${s} --machine ${machine} -o ${WORK}/${n}.compensated.ngc)
  run(${n}.interpret interpret ${s} --machine ${machine})
  run(${n}.measured.csv -q simulate measure --truth machines/sample/truth.yaml --program ${s}
      --noise 0.5um --seed 7 -o ${WORK}/${n}.measured.csv)
endforeach()
run(grid.predict-all.csv predict machines/sample/measured-grid.csv --machine ${machine}
    --model all -o ${WORK}/grid.predict-all.csv)
# The summary files written beside the outputs.
file(GLOB summaries RELATIVE ${WORK} ${WORK}/*.summary.json)
list(SORT summaries)
foreach(f ${summaries})
  file(SHA256 ${WORK}/${f} h)
  string(APPEND lines "${h}  ${f}\n")
endforeach()

if(UPDATE)
  file(WRITE ${golden} "${lines}")
  message(STATUS "recorded ${golden}")
  return()
endif()
file(READ ${golden} expected)
if(NOT expected STREQUAL lines)
  file(WRITE ${WORK}/outputs.sha256 "${lines}")
  execute_process(COMMAND diff ${golden} ${WORK}/outputs.sha256 OUTPUT_VARIABLE d)
  message(FATAL_ERROR "outputs differ from the golden hashes (outputs kept in ${WORK}):\n${d}")
endif()
message(STATUS "golden outputs: all identical")
