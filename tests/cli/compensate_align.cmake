# `abbe compensate --align best-fit` (docs/compensation.md, "Only what the
# set-up leaves"): the summary names the set-up taken out and the part's
# deviation before and after it.
add_test(NAME cli_compensate_align_best_fit
         COMMAND $<TARGET_FILE:abbe> compensate ${PROJECT_SOURCE_DIR}/nc-samples/thesis-toolpath-1.ngc
                 --machine ${CMAKE_CURRENT_SOURCE_DIR}/data/machines/sample.yaml --align best-fit
                 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_compensate_align.ngc)
set_tests_properties(cli_compensate_align_best_fit PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION
  "max correction [0-9.]+ µm.*\n  --align best-fit: the set-up takes out a rotation \\([-0-9., ]+\\) µrad and a shift \\([-0-9., ]+\\) µm of the part's centroid; predicted part max \\|e\\| [0-9.]+ µm, [0-9.]+ µm after the set-up")
