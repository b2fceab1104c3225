# Command-level tests of `abbe import laser` (docs/formats.md, "Laser
# calibration export"): the runs file goes into `abbe iso230`, the table rows
# carry the uncertainty column, and a unit that does not fit the component is
# refused with file, line, column and field (exit 1).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_import_laser cli_import_laser_work cli
                  DEFINES -DDATA=${CMAKE_CURRENT_SOURCE_DIR}/data/laser)
  return()
endif()

include(${CMAKE_CURRENT_LIST_DIR}/lib/refusal_helpers.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/lib/script_helpers.cmake)
start_with_previous_output(${WORK}/out.csv)

run(${ABBE} import laser ${DATA}/x-positioning-um.csv -o ${WORK}/runs.csv
    --table ${WORK}/table.csv)
expect_file_matches(${WORK}/runs.csv
  "^axis,component,target_mm,run,direction,deviation\nX,EXX,0,1,up,0\nX,EXX,0,1,down,-1.2\n"
  "unexpected runs file")
expect_file_matches(${WORK}/table.csv
  "^axis,component,position_mm,direction,value,uncertainty\nX,EXX,0,fwd,0\\.1[0-9]*,0\\.057735026918962[0-9]*\n"
  "unexpected table")
run(${ABBE} iso230 ${WORK}/runs.csv)
if(NOT run_out MATCHES "EXX")
  message(FATAL_ERROR "iso230 of the imported runs:\n${run_out}")
endif()

# Arc-seconds: µrad in the runs file (0.5″ = 2.42406840554768 µrad).
run(${ABBE} import laser ${DATA}/x-pitch-arcsec.csv)
if(NOT run_out MATCHES "\nX,EBX,100,1,up,2\\.424068405547")
  message(FATAL_ERROR "import laser arcsec:\n${run_out}")
endif()

# A linear component in arc-seconds: refused, the output left as it was.
file(WRITE ${WORK}/bad.csv "# axis: X\n# component: EXX\n# units: arcsec\ntarget,run,direction,reading\n0,1,up,1\n")
refused_untouched(1 "arcsec for EXX"
                  "bad.csv:3:10 \\[units\\]: error: EXX is linear but the unit arcsec is angular"
                  ${WORK}/out.csv ${ABBE} import laser ${WORK}/bad.csv -o ${WORK}/out.csv)

# Several components in one file (one section each): every component in the
# runs file and in the table.
run(${ABBE} import laser ${DATA}/three-components.csv -o ${WORK}/three-runs.csv
    --table ${WORK}/three-table.csv)
expect_file_matches(${WORK}/three-runs.csv
  "\nX,EXX,0,1,up,0\n.*\nX,EBX,200,1,up,[34][0-9.]*\n.*\nY,EYY,0,2,up,1\\.9[0-9]*\n$"
  "unexpected runs file of three-components.csv")
expect_file_matches(${WORK}/three-table.csv
  "^axis,component,position_mm,direction,value,uncertainty\nX,EXX,0,fwd,.*\nX,EBX,200,mean,[45][0-9.]*,[01][0-9.]*\n.*Y,EYY,0,mean,[12][0-9.]*,"
  "unexpected table of three-components.csv")
