# Command-level tests of `abbe diagnose` and `abbe import plugplate` (label
# cli), run with `cmake -P`: a hidden reversal found in simulated data, the
# JSON report keys, the overlay accepted by predict and diagnose (--extend),
# the plug-plate importer, and errors.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_diagnose
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_diagnose -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_diagnose PROPERTIES LABELS cli TIMEOUT 300)
  # The larger hidden-effect sweep (200 seeds instead of 40): ctest -L slow.
  add_test(NAME diagnose_hidden_effect_sweep
           COMMAND $<TARGET_FILE:abbe_tests> --gtest_filter=DiagnoseHiddenEffect.*)
  set_tests_properties(diagnose_hidden_effect_sweep PROPERTIES LABELS slow TIMEOUT 1800
                       COST 500 ENVIRONMENT ABBE_DIAGNOSE_SEEDS=200)
  # The honest harness on real measurement designs, 200 seeds per design,
  # in three parts of about equal time (the toolpath alone is a third) so
  # that `ctest --parallel` spreads them over the cores; COST makes ctest
  # start them first on a fresh build, where it has no timings yet.
  set(grids "DiagnoseDesigns.Grid:DiagnoseDesigns.GridIrregular:DiagnoseDesigns.GridWithoutDirectionsInferred")
  foreach(part toolpath grids others)
    if(part STREQUAL "toolpath")
      set(filter DiagnoseDesigns.Toolpath)
    elseif(part STREQUAL "grids")
      set(filter ${grids})
    else()
      set(filter "DiagnoseDesigns.*-DiagnoseDesigns.Toolpath:${grids}")
    endif()
    add_test(NAME diagnose_designs_sweep_${part}
             COMMAND $<TARGET_FILE:abbe_tests> --gtest_filter=${filter})
    set_tests_properties(diagnose_designs_sweep_${part} PROPERTIES LABELS slow TIMEOUT 3600
                         COST 1000 ENVIRONMENT ABBE_DIAGNOSE_SEEDS=200)
  endforeach()
  return()
endif()

include(${SRC}/tests/cli/lib/script_helpers.cmake)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(M ${SRC}/machines/sample)
set(P ${SRC}/tests/data/plugplate)

# A large reversal of Y hidden in a grid measurement of the sample machine.
run(${ABBE} simulate measure --truth ${M}/truth.yaml --grid 100 --inject reversal:Y:12um
    --noise 0.5um --seed 3 -o ${WORK}/rev.csv)
run(${ABBE} diagnose --machine ${M}/machine.yaml --measured ${WORK}/rev.csv
    --out ${WORK}/report.json --overlay ${WORK}/overlay.yaml)
string(FIND "${run_out}" "reversal" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the summary names no reversal:\n${run_out}")
endif()
file(READ ${WORK}/report.json js)
foreach(key model n_points models baseline effects extended blind_spots)
  string(JSON v ERROR_VARIABLE e GET "${js}" ${key})
  if(e)
    message(FATAL_ERROR "report.json lacks ${key}")
  endif()
endforeach()
string(JSON kind GET "${js}" effects 0 kind)
string(JSON axis GET "${js}" effects 0 axis)
if(NOT kind STREQUAL "reversal" OR NOT axis STREQUAL "Y")
  message(FATAL_ERROR "first effect is ${kind} ${axis}, expected reversal Y")
endif()
string(JSON gain GET "${js}" extended gain_percent)
if(gain LESS 50)
  message(FATAL_ERROR "gain ${gain} % too small")
endif()

# The overlay: predict accepts it, and diagnosing again with it finds no reversal.
run(${ABBE} predict ${WORK}/rev.csv --machine ${M}/machine.yaml --extend ${WORK}/overlay.yaml
    -o ${WORK}/pred.csv)
run(${ABBE} diagnose --machine ${M}/machine.yaml --measured ${WORK}/rev.csv
    --extend ${WORK}/overlay.yaml --out ${WORK}/again.json)
file(READ ${WORK}/again.json js2)
string(FIND "${js2}" "\"reversal\"" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "the reversal is still found with --extend")
endif()

# Plug plates.
run(${ABBE} import plugplate ${P}/D8131_1 -o ${WORK}/p1.csv)
file(STRINGS ${WORK}/p1.csv lines)
list(LENGTH lines n)
if(NOT n EQUAL 83)
  message(FATAL_ERROR "p1.csv has ${n} lines, expected 83")
endif()
run(${ABBE} diagnose --machine ${P}/machine.yaml --measured ${WORK}/p1.csv)
# The plate's rotation is datum (the plate is re-placed), reported apart
# from the effects: about +506 µrad for plate 8131.
string(REGEX MATCH "setup rotation about Z \\[8131\\] 50[5-8] ±" rot "${run_out}")
if(NOT rot)
  message(FATAL_ERROR "plate 8131: rotation not found in the datum:\n${run_out}")
endif()

# One plate's extended model on a plate of the same batch (8132): the
# summary and the JSON say what it does after 8132's own datum
# (tests/unit/diagnose_plugplate_test.cpp: 7.93 → 6.75 µm).
run(${ABBE} diagnose --machine ${P}/machine.yaml --measured ${WORK}/p1.csv
    --overlay ${WORK}/p1-overlay.yaml)
run(${ABBE} import plugplate ${P}/D8132_1 -o ${WORK}/p2.csv)
run(${ABBE} diagnose --machine ${P}/machine.yaml --measured ${WORK}/p2.csv
    --extend ${WORK}/p1-overlay.yaml --out ${WORK}/p2.json)
string(REGEX MATCH "the earlier overlay \\(--extend, 1 term\\) on these data: rms after the datum 7\\.9[0-9]+ → 6\\.[0-9]+ µm \\(\\+1[0-9]\\.[0-9] %\\)"
       tr "${run_out}")
if(NOT tr)
  message(FATAL_ERROR "8131's model on 8132: no transfer line:\n${run_out}")
endif()
file(READ ${WORK}/p2.json js3)
string(JSON change GET "${js3}" extend_check change_percent)
if(change LESS 10)
  message(FATAL_ERROR "8131's model on 8132: ${change} %, expected about +15 %")
endif()
# Two of 8132's holes lie outside the box 8131's model was fitted on: said.
string(JSON outside GET "${js3}" extend_check outside_domain)
string(JSON warning GET "${js3}" extend_check warnings 0)
if(NOT outside EQUAL 2 OR NOT warning MATCHES "^2 of the 82 points lie outside the domain")
  message(FATAL_ERROR "8131's model on 8132: ${outside} points outside, warning: ${warning}")
endif()

# Errors: exit code 1 with file and line.
file(WRITE ${WORK}/bad.csv "x,y,z,dx\n1,2,3,4\n1,2,zz,4\n")
expect_failure("bad.csv:3:5" ${ABBE} diagnose --machine ${M}/machine.yaml --measured ${WORK}/bad.csv)
file(WRITE ${WORK}/bad.yaml "format: abbe-overlay-1\neffects:\n  - term: wobble\n    coef: [1]\n")
expect_failure("bad.yaml:3" ${ABBE} predict ${WORK}/rev.csv --machine ${M}/machine.yaml
               --extend ${WORK}/bad.yaml)
file(WRITE ${WORK}/bad_plate "Plug Plate: 1\nMeas X Meas Y Nom X Nom Y Err X Err Y\n1 2 1 2 0\n")
expect_failure("bad_plate:3" ${ABBE} import plugplate ${WORK}/bad_plate -o ${WORK}/x.csv)
if(EXISTS ${WORK}/x.csv)
  message(FATAL_ERROR "a failed import left its output")
endif()

# abbe import ballbar (ISO 230-4 readings, docs/formats.md): any column
# order, header case; a circle in XY both ways becomes dn data that
# diagnose reads, with the statement about dynamic effects.
set(bb "Angle,dr,Plane,Radius,cx,cy,cz,Feed,Direction\n")
foreach(way ccw cw)
  foreach(a RANGE 0 350 10)
    string(APPEND bb "${a},0.1,XY,150,-450,-200,-150,1000,${way}\n")
  endforeach()
endforeach()
file(WRITE ${WORK}/bb.csv "${bb}")
run(${ABBE} import ballbar ${WORK}/bb.csv -o ${WORK}/bb-measured.csv)
file(STRINGS ${WORK}/bb-measured.csv lines)
list(LENGTH lines n)
if(NOT n EQUAL 73)
  message(FATAL_ERROR "bb-measured.csv has ${n} lines, expected 73")
endif()
run(${ABBE} diagnose --machine ${P}/machine.yaml --measured ${WORK}/bb-measured.csv)
string(FIND "${run_out}" "servo mismatch and reversal spikes are dynamic" at)
if(at EQUAL -1)
  message(FATAL_ERROR "diagnose of a circular test says nothing about dynamic effects:\n${run_out}")
endif()
file(WRITE ${WORK}/bad_bb.csv "plane,radius,cx,cy,cz,feed,direction,angle,dr\nXY,150,0,0,0,1000,up,0,1\n")
expect_failure("bad_bb.csv:2:19 [direction]" ${ABBE} import ballbar ${WORK}/bad_bb.csv
               -o ${WORK}/bb-x.csv)
if(EXISTS ${WORK}/bb-x.csv)
  message(FATAL_ERROR "a failed ballbar import left its output")
endif()

# Points the machine cannot reach: a real CAM program written in the part's
# coordinates (x 0…208, y 0…32 mm; the sample machine's X and Y travels end
# at 0) measured on the virtual machine, then diagnosed. Both commands warn
# (on stderr, with the count per axis and the first lines), the summary and
# the JSON say it too, and both still exit 0.
execute_process(COMMAND ${ABBE} simulate measure --truth ${M}/truth.yaml
                        --program ${SRC}/tests/data/cam-corpus/led-floor-1079-light-holder.nc
                        -o ${WORK}/part-frame.csv
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT err MATCHES "379 of 380 points outside the travel \\(points per axis: X 321, Y 244, Z 11\\), first on lines 15, ")
  message(FATAL_ERROR "simulate measure beyond the travel: exit ${rc}, no warning:\n${err}")
endif()
execute_process(COMMAND ${ABBE} diagnose --machine ${M}/machine.yaml
                        --measured ${WORK}/part-frame.csv --out ${WORK}/part-frame.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT err MATCHES "379 of 380 points outside the travel.*machine coordinates"
   OR NOT out MATCHES "warning: [^\n]*379 of 380 points outside the travel")
  message(FATAL_ERROR "diagnose beyond the travel: exit ${rc}, no warning:\n${out}\n${err}")
endif()
file(READ ${WORK}/part-frame.json js)
string(JSON n GET "${js}" outside_travel_points)
if(NOT n EQUAL 379)
  message(FATAL_ERROR "report.json: outside_travel_points ${n}, expected 379")
endif()
# Within the travel (the grid above): no such warning.
file(READ ${WORK}/report.json js)
string(JSON n GET "${js}" outside_travel_points)
string(FIND "${js}" "travel_warning" at)
if(NOT n EQUAL 0 OR NOT at EQUAL -1)
  message(FATAL_ERROR "a grid within the travel: outside_travel_points ${n}, travel_warning at ${at}")
endif()

# --table-uncertainty N: the tables' uncertainty (the machine file's
# `uncertainty`) in every effect's u. The walk-through's grid against the
# sample machine with its campaign's uncertainty: the summary says so and
# splits the drift's u into the data's and the tables' parts, and the JSON
# gives both; a machine without any uncertainty is refused by name.
execute_process(COMMAND ${ABBE} diagnose --machine ${M}/machine-uncertainty.yaml
                        --measured ${M}/measured-grid.csv --table-uncertainty 20
                        --out ${WORK}/tables.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "every u holds the data's and the tables' uncertainty[^\n]*20 draws"
   OR NOT out MATCHES "u from the data and from the tables: value [0-9.e+-]+ and [0-9.e+-]+ µm; τ ")
  message(FATAL_ERROR "diagnose --table-uncertainty: exit ${rc}:\n${out}\n${err}")
endif()
file(READ ${WORK}/tables.json js)
string(JSON draws GET "${js}" table_uncertainty draws)
string(JSON u_data GET "${js}" effects 0 stderr_data um)
string(JSON u_tables GET "${js}" effects 0 stderr_tables um)
string(JSON u GET "${js}" effects 0 stderr um)
if(NOT draws EQUAL 20 OR NOT u_tables GREATER 0 OR NOT u GREATER u_data)
  message(FATAL_ERROR "tables.json: draws ${draws}, u ${u} (data ${u_data}, tables ${u_tables})")
endif()
# Without the option on that machine: 50 draws by default; with 0 the
# summary says the u are the data's alone and how to add the tables'; 1
# draw is refused.
execute_process(COMMAND ${ABBE} diagnose --machine ${M}/machine-uncertainty.yaml
                        --measured ${M}/measured-grid.csv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "every u holds the data's and the tables' uncertainty[^\n]*50 draws")
  message(FATAL_ERROR "diagnose on a machine with an uncertainty, not propagated: exit ${rc}:\n${out}")
endif()
execute_process(COMMAND ${ABBE} diagnose --machine ${M}/machine-uncertainty.yaml
                        --measured ${M}/measured-grid.csv --table-uncertainty 0
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "every u is the data's alone \\(--table-uncertainty 0\\): the machine file gives its tables' uncertainty, and --table-uncertainty N adds it"
   OR out MATCHES "u from the data and from the tables")
  message(FATAL_ERROR "diagnose --table-uncertainty 0, no hint: exit ${rc}:\n${out}")
endif()
execute_process(COMMAND ${ABBE} diagnose --machine ${M}/machine-uncertainty.yaml
                        --measured ${M}/measured-grid.csv --table-uncertainty 1
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "--table-uncertainty\\]: error: --table-uncertainty needs at least 2 draws")
  message(FATAL_ERROR "diagnose --table-uncertainty 1: exit ${rc}:\n${err}")
endif()
execute_process(COMMAND ${ABBE} diagnose --machine ${M}/machine.yaml
                        --measured ${M}/measured-grid.csv --table-uncertainty 20
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "machine.yaml \\[uncertainty\\]: error: --table-uncertainty: nothing to propagate")
  message(FATAL_ERROR "--table-uncertainty without an uncertainty: exit ${rc}:\n${err}")
endif()
