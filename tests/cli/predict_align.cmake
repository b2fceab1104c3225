# Command-level tests of `abbe predict --align` (docs/models.md, "The part").
# Included from tests/CMakeLists.txt; the error cases run in script mode.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(ABBE_ALIGN_DATA ${CMAKE_CURRENT_SOURCE_DIR}/data/align)

  # The thesis toolpath, every model: the part table (absolute and aligned
  # rows, the set-up) after the usual summary.
  add_test(NAME cli_predict_align_best_fit
           COMMAND $<TARGET_FILE:abbe> predict ${PROJECT_SOURCE_DIR}/nc-samples/thesis-toolpath-1.ngc
                   --machine ${CMAKE_CURRENT_SOURCE_DIR}/data/machines/sample.yaml --model all
                   --align best-fit --summary-only)
  set_tests_properties(cli_predict_align_best_fit PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "part \\([0-9]+ cutting points\\), aligned by best-fit:\n.*\n  htm +absolute +[0-9.]+ +[0-9.]+ +[0-9.]+ +[0-9.]+ +[0-9.]+\n +aligned +[0-9.]+ +[0-9.]+ +[0-9.]+ +[0-9.]+ +[0-9.]+\n +setup +rotation \\([-0-9., ]+\\) µrad, centroid shift \\([-0-9., ]+\\) µm\n  ae-arm +absolute")

  # Rigid-body-only errors: nothing remains after the best fit (absolute > 0).
  add_test(NAME cli_predict_align_rigid_only_gives_zero
           COMMAND $<TARGET_FILE:abbe> predict ${PROJECT_SOURCE_DIR}/nc-samples/thesis-toolpath-1.ngc
                   --machine ${ABBE_ALIGN_DATA}/rigid-only.yaml --model ae-arm
                   --align best-fit --summary-only)
  set_tests_properties(cli_predict_align_rigid_only_gives_zero PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "ae-arm +absolute +[0-9.]+ +[0-9.]+ +[0-9.]+ +[1-9][0-9.]* +[1-9][0-9.]*\n +aligned +0\\.0000 +0\\.0000 +0\\.0000 +0\\.0000 +0\\.0000\n")

  # 3-2-1 on the faces of a block (CSV points), per-point aligned columns.
  add_test(NAME cli_predict_align_datums
           COMMAND $<TARGET_FILE:abbe> predict ${ABBE_ALIGN_DATA}/block-points.csv
                   --machine ${CMAKE_CURRENT_SOURCE_DIR}/data/machines/sample.yaml
                   --align datums --datum-primary 2-31 --datum-secondary 32-51
                   --datum-tertiary 52-61)
  set_tests_properties(cli_predict_align_datums PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "^x,y,z,px,py,pz,dx,dy,dz,d,adx,ady,adz,ad,line\n-600,-300,-250,[^\n]*,2\n.*aligned by datums \\(primary 30, secondary 20, tertiary 10 points\\)")

  # JSON: the aligned keys per point and the alignment member of the summary.
  add_test(NAME cli_predict_align_json
           COMMAND $<TARGET_FILE:abbe> predict ${ABBE_ALIGN_DATA}/block-points.csv
                   --machine ${CMAKE_CURRENT_SOURCE_DIR}/data/machines/sample.yaml --model dual
                   --align best-fit --format json)
  set_tests_properties(cli_predict_align_json PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "\"dual\": \\{\"px\": [^}]*\"dx2\": [^}]*\"adx\": [^}]*\"ad\": [^}]*\\}.*\"alignment\": \\{.*\"method\": \"best-fit\",.*\"part_points\": 60")

  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_predict_align_errors cli_predict_align_work cli
                  DEFINES -DMACHINE=${CMAKE_CURRENT_SOURCE_DIR}/data/machines/sample.yaml
                          -DDATA=${ABBE_ALIGN_DATA})
  return()
endif()

# ---- script mode: exit codes and messages; an existing output is left as it was ----
include(${CMAKE_CURRENT_LIST_DIR}/lib/refusal_helpers.cmake)
start_with_previous_output(${WORK}/out.csv)
function(expect code what pattern)
  refused_untouched(${code} "${what}" "${pattern}" ${WORK}/out.csv
                    ${ABBE} predict ${ARGN} --machine ${MACHINE} -o ${WORK}/out.csv)
endfunction()

expect(1 "bad line set" "<command line>:3 \\[--datum-primary\\]: error: expected a line number"
       ${DATA}/block-points.csv --align datums --datum-primary 2-x --datum-secondary 32-51
       --datum-tertiary 52-61)
expect(1 "collinear primary datum" "block-points.csv.*primary datum's points are collinear"
       ${DATA}/block-points.csv --align datums --datum-primary 2-6 --datum-secondary 32-51
       --datum-tertiary 52-61)
expect(1 "empty tertiary datum" "block-points.csv.*tertiary datum needs at least 1"
       ${DATA}/block-points.csv --align datums --datum-primary 2-31 --datum-secondary 32-51
       --datum-tertiary 900)
expect(1 "collinear part" "line-points.csv.*collinear" ${DATA}/line-points.csv --align best-fit)
expect(2 "datums without sets" "--align datums needs --datum-secondary"
       ${DATA}/block-points.csv --align datums --datum-primary 2-31)
expect(2 "a datum set without --align datums" "--datum-primary needs --align datums"
       ${DATA}/block-points.csv --datum-primary 2-31)
expect(2 "unknown alignment" "--align" ${DATA}/block-points.csv --align cmm)
