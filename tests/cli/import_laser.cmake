# Command-level tests of `abbe import laser` (docs/formats.md, "Laser
# calibration export"): the runs file goes into `abbe iso230`, the table rows
# carry the uncertainty column, and a unit that does not fit the component is
# refused with file, line, column and field (exit 1).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_import_laser
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe>
                   -DDATA=${CMAKE_CURRENT_SOURCE_DIR}/data/laser
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_import_laser_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_import_laser PROPERTIES LABELS cli)
  return()
endif()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# import_checked(INPUT NAME RUNS_REGEX TABLE_REGEX): imports INPUT into
# NAME-runs.csv and NAME-table.csv and checks both against their patterns.
function(import_checked input name runs_regex table_regex)
  execute_process(COMMAND ${ABBE} import laser ${input} -o ${WORK}/${name}-runs.csv
                          --table ${WORK}/${name}-table.csv
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "import laser ${input}: exit ${rc}\n${err}")
  endif()
  file(READ ${WORK}/${name}-runs.csv runs)
  if(NOT runs MATCHES "${runs_regex}")
    message(FATAL_ERROR "unexpected runs file of ${input}:\n${runs}")
  endif()
  file(READ ${WORK}/${name}-table.csv table)
  if(NOT table MATCHES "${table_regex}")
    message(FATAL_ERROR "unexpected table of ${input}:\n${table}")
  endif()
endfunction()

import_checked(${DATA}/x-positioning-um.csv x
  "^axis,component,target_mm,run,direction,deviation\nX,EXX,0,1,up,0\nX,EXX,0,1,down,-1.2\n"
  "^axis,component,position_mm,direction,value,uncertainty\nX,EXX,0,fwd,0\\.1[0-9]*,0\\.057735026918962[0-9]*\n")
execute_process(COMMAND ${ABBE} iso230 ${WORK}/x-runs.csv RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "EXX")
  message(FATAL_ERROR "iso230 of the imported runs: exit ${rc}\n${out}${err}")
endif()

# Arc-seconds: µrad in the runs file (0.5″ = 2.42406840554768 µrad).
execute_process(COMMAND ${ABBE} import laser ${DATA}/x-pitch-arcsec.csv RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "\nX,EBX,100,1,up,2\\.424068405547")
  message(FATAL_ERROR "import laser arcsec: exit ${rc}\n${out}${err}")
endif()

# A linear component in arc-seconds: refused, the output left as it was.
file(WRITE ${WORK}/bad.csv "# axis: X\n# component: EXX\n# units: arcsec\ntarget,run,direction,reading\n0,1,up,1\n")
file(WRITE ${WORK}/out.csv "previous contents\n")
execute_process(COMMAND ${ABBE} import laser ${WORK}/bad.csv -o ${WORK}/out.csv
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "bad.csv:3:10 \\[units\\]: error: EXX is linear but the unit arcsec is angular")
  message(FATAL_ERROR "arcsec for EXX: exit ${rc}\n${err}")
endif()
file(READ ${WORK}/out.csv contents)
if(NOT contents STREQUAL "previous contents\n")
  message(FATAL_ERROR "the output was changed by a refused import")
endif()

# Several components in one file (one section each): every component in the
# runs file and in the table.
import_checked(${DATA}/three-components.csv three
  "\nX,EXX,0,1,up,0\n.*\nX,EBX,200,1,up,[34][0-9.]*\n.*\nY,EYY,0,2,up,1\\.9[0-9]*\n$"
  "^axis,component,position_mm,direction,value,uncertainty\nX,EXX,0,fwd,.*\nX,EBX,200,mean,[45][0-9.]*,[01][0-9.]*\n.*Y,EYY,0,mean,[12][0-9.]*,")
