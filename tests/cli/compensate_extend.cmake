# `abbe compensate --extend` and `abbe verify --extend`: the compensated
# program of the extended model passes verify with the same overlay, and
# verify with the plain model sees exactly the overlay's term. The overlay
# is written by hand: squareness X→Z of 10 µrad, dz = 0.01·x µm, normal to
# the XY rectangle of thesis-toolpath-1 (x from -350 to -650 mm: up to
# 6.5 µm). Script mode (cmake -P).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_compensate_extend
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_compensate_extend_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_compensate_extend PROPERTIES LABELS "cli;compensate")
  return()
endif()
include(${CMAKE_CURRENT_LIST_DIR}/lib/script_helpers.cmake)

set(MACHINE ${SRC}/machines/sample/machine.yaml)
set(PROGRAM ${SRC}/nc-samples/thesis-toolpath-1.ngc)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/overlay.yaml "format: abbe-overlay-1
model: ae-arm
machine: sample
effects:
  - term: squareness
    axis: X
    direction: Z
    coef: [10]
")

function(verify_max out_var)
  run(${ABBE} verify ${ARGN})
  if(NOT run_out MATCHES "\n  max ([0-9.]+) µm, tol")
    message(FATAL_ERROR "no max in the verify output:\n${run_out}")
  endif()
  set(${out_var} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

run(${ABBE} compensate ${PROGRAM} --machine ${MACHINE} --extend ${WORK}/overlay.yaml
    -o ${WORK}/extended.ngc)
run(${ABBE} compensate ${PROGRAM} --machine ${MACHINE} -o ${WORK}/plain.ngc)
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/plain.ngc ${WORK}/extended.ngc
                RESULT_VARIABLE same)
if(same EQUAL 0)
  message(FATAL_ERROR "--extend did not change the compensated program")
endif()

# The extended model's prediction of its compensated program is the nominal path.
verify_max(with ${WORK}/extended.ngc --against ${PROGRAM} --machine ${MACHINE}
           --extend ${WORK}/overlay.yaml --tol 1 --check)
if(with GREATER 1)
  message(FATAL_ERROR "verify --extend: max ${with} µm > 1 µm")
endif()
# The plain model sees the overlay's term: 6.5 µm at x = -650 (± the 1 µm tol).
verify_max(without ${WORK}/extended.ngc --against ${PROGRAM} --machine ${MACHINE} --tol 1)
if(without LESS 5.5 OR without GREATER 7.5)
  message(FATAL_ERROR "verify without --extend: max ${without} µm, expected 6.5 ± 1 µm")
endif()
# And the plainly compensated program, predicted with the overlay, is off by it too.
verify_max(plain ${WORK}/plain.ngc --against ${PROGRAM} --machine ${MACHINE}
           --extend ${WORK}/overlay.yaml --tol 1)
if(plain LESS 5.5 OR plain GREATER 7.5)
  message(FATAL_ERROR "plain program with --extend: max ${plain} µm, expected 6.5 ± 1 µm")
endif()

# An overlay made by `abbe diagnose` from the sample measurement (its hidden
# cause, a thermal drift of Z, is named as the catalogue's warm-up drift:
# docs/getting-started.md §6), applied by compensate and verify alike.
run(${ABBE} -q diagnose --machine ${MACHINE} --measured ${SRC}/machines/sample/measured-grid.csv
    --overlay ${WORK}/diagnosed.yaml)
file(READ ${WORK}/diagnosed.yaml diagnosed)
if(NOT diagnosed MATCHES "term: thermal_drift")
  message(FATAL_ERROR "the diagnosed overlay has no term:\n${diagnosed}")
endif()
run(${ABBE} compensate ${PROGRAM} --machine ${MACHINE} --extend ${WORK}/diagnosed.yaml
    -o ${WORK}/diagnosed.ngc)
verify_max(diag ${WORK}/diagnosed.ngc --against ${PROGRAM} --machine ${MACHINE}
           --extend ${WORK}/diagnosed.yaml --tol 1 --check)

# A bad overlay is refused naming the file and field; no output is written.
file(WRITE ${WORK}/bad.yaml "format: abbe-overlay-1\neffects:\n  - term: scale\n    axis: Q\n")
expect_failure("bad.yaml:4" ${ABBE} compensate ${PROGRAM} --machine ${MACHINE}
               --extend ${WORK}/bad.yaml -o ${WORK}/bad-out.ngc)
if(EXISTS ${WORK}/bad-out.ngc)
  message(FATAL_ERROR "an output was written with a bad overlay")
endif()
expect_failure("missing.yaml" ${ABBE} verify ${WORK}/extended.ngc --against ${PROGRAM}
               --machine ${MACHINE} --extend ${WORK}/missing.yaml)

# Overlays know their domain (issue 16): a smooth function of t fitted over
# a 6 s window (degree 6, 6 µm at its end), applied along the program's
# own clock (65 s) far beyond it. With the domain it is held at its end value and
# predict warns once; without it the polynomial explodes, and the absurd
# correction is refused (exit 1) by predict and compensate alike.
set(timed_effects "effects:
  - term: unexplained
    direction: Z
    vars: [t]
    degree: 6
    lo: [-2000, -2000, -2000, 0]
    hi: [2000, 2000, 2000, 6]
    coef: [1, 1, 1, 1, 1, 1]
")
file(WRITE ${WORK}/timed.yaml "format: abbe-overlay-1
model: ae-arm
domain:
  min: [-2000, -2000, -2000]
  max: [2000, 2000, 2000]
  time: [0, 6]
${timed_effects}")
file(WRITE ${WORK}/timed-old.yaml "format: abbe-overlay-1\nmodel: ae-arm\n${timed_effects}")
foreach(ext "" timed)
  set(args ${PROGRAM} --machine ${MACHINE} --summary-only --summary-json ${WORK}/sum${ext}.json)
  if(ext)
    list(APPEND args --extend ${WORK}/${ext}.yaml)
  endif()
  execute_process(COMMAND ${ABBE} predict ${args} RESULT_VARIABLE rc ERROR_VARIABLE err
                  OUTPUT_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "predict ${ext}: exit ${rc}\n${err}")
  endif()
  file(READ ${WORK}/sum${ext}.json js)
  string(JSON max${ext} GET "${js}" models 0 max_d_um)
endforeach()
if(NOT err MATCHES "timed.yaml: [0-9]+ of [0-9]+ points outside the domain")
  message(FATAL_ERROR "predict with a time term beyond its window: no domain warning\n${err}")
endif()
# At most the end value (6 µm) more than the plain model, not metres.
if(maxtimed GREATER_EQUAL 1000 OR NOT maxtimed GREATER max)
  message(FATAL_ERROR "predict --extend timed.yaml: max ${maxtimed} µm (plain ${max} µm)")
endif()
expect_failure("beyond the 1000 µm an overlay may correct, refused" ${ABBE} predict ${PROGRAM}
               --machine ${MACHINE} --summary-only --extend ${WORK}/timed-old.yaml)
expect_failure("beyond the 1000 µm an overlay may correct, refused" ${ABBE} compensate ${PROGRAM}
               --machine ${MACHINE} --extend ${WORK}/timed-old.yaml --extend-time 600
               -o ${WORK}/absurd.ngc)
if(EXISTS ${WORK}/absurd.ngc)
  message(FATAL_ERROR "an absurd correction was written")
endif()
# Compensate at a time inside the window: accepted.
run(${ABBE} compensate ${PROGRAM} --machine ${MACHINE} --extend ${WORK}/timed.yaml
    --extend-time 3 -o ${WORK}/timed.ngc)
