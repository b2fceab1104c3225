# `abbe compensate --align best-fit|datums` (docs/compensation.md, "Only what the
# set-up leaves"): the summary names the set-up taken out and the part's
# deviation before and after it.
# One run of `abbe compensate` on thesis-toolpath-1 with the sample
# machine and the given options, its output `out`, its output text matched
# against `expected`.
function(compensate_align_test name out expected)
  add_test(NAME ${name}
           COMMAND $<TARGET_FILE:abbe> compensate ${PROJECT_SOURCE_DIR}/nc-samples/thesis-toolpath-1.ngc
                   --machine ${CMAKE_CURRENT_SOURCE_DIR}/data/machines/sample.yaml ${ARGN}
                   -o ${CMAKE_CURRENT_BINARY_DIR}/${out})
  set_tests_properties(${name} PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "${expected}")
endfunction()

compensate_align_test(cli_compensate_align_best_fit cli_compensate_align.ngc
  "max correction [0-9.]+ µm.*\n  --align best-fit: the set-up takes out a rotation \\([-0-9., ]+\\) µrad and a shift \\([-0-9., ]+\\) µm of the part's centroid; predicted part max \\|e\\| [0-9.]+ µm, [0-9.]+ µm after the set-up"
  --align best-fit)

# 3-2-1 datums (the rectangle's bottom, its first side, the corner after it):
# the set-up and figures of `abbe predict --align datums` with the same sets
# (rotation (-9.207, -12.514, -3.669) µrad, aligned max |d| 5.3389 µm; the
# best fit's rotation is (-9.250, -12.478, -12.464) µrad, 4.2480 µm).
compensate_align_test(cli_compensate_align_datums cli_compensate_align_datums.ngc
  "max correction [0-9.]+ µm.*\n  --align datums: the set-up takes out a rotation \\(-9\\.207, -12\\.514, -3\\.669\\) µrad and a shift \\([-0-9., ]+\\) µm of the part's centroid; predicted part max \\|e\\| 19\\.7853 µm, 5\\.3389 µm after the set-up"
  --align datums --datum-primary 18-21 --datum-secondary 18 --datum-tertiary 19)
# A datum set without --align datums is a usage error (the message of
# align_options, which returns exit code 2), as in predict.
compensate_align_test(cli_compensate_align_datum_without_datums cli_compensate_align_unused.ngc
  "^abbe compensate: --datum-primary needs --align datums\n$"
  --datum-primary 18-21)
