# Command-level tests of `abbe predict --uncertainty N` (docs/models.md,
# "Uncertainty of the prediction"). Included from tests/CMakeLists.txt; the
# byte-for-byte and error cases run in script mode.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(ABBE_U_MACHINE ${PROJECT_SOURCE_DIR}/machines/sample/machine-uncertainty.yaml)

  # A program: the u columns per point and the summary with U (k = 2).
  add_test(NAME cli_predict_uncertainty_program
           COMMAND $<TARGET_FILE:abbe> predict ${PROJECT_SOURCE_DIR}/nc-samples/thesis-toolpath-1.ngc
                   --machine ${ABBE_U_MACHINE} --uncertainty 20)
  set_tests_properties(cli_predict_uncertainty_program PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "^x,y,z,px,py,pz,dx,dy,dz,d,u_dx,u_dy,u_dz,line\n[^\n]*,[0-9.]+,[0-9.]+,[0-9.]+,[0-9]+\n.*uncertainty \\(Monte Carlo, GUM Supplement 1: 20 draws, seed 1\\): value ± U, U = k·u with k = 2\n  propagated: laser 0.05 µm \\+ 0.5 ppm \\(positioning\\); components EYX 0.3 µm,[^\n]*; reflector points 2 mm; squareness [^\n]*\n.*\n  ae-arm  cutting +[0-9.]+ ± [0-9.]+")

  # --model all, JSON: the u keys in every model's object and the summary member.
  add_test(NAME cli_predict_uncertainty_json
           COMMAND $<TARGET_FILE:abbe> predict ${PROJECT_SOURCE_DIR}/machines/sample/measured-grid.csv
                   --machine ${ABBE_U_MACHINE} --model all --uncertainty 5 --format json)
  set_tests_properties(cli_predict_uncertainty_json PROPERTIES LABELS cli
    PASS_REGULAR_EXPRESSION
    "\"htm\": \\{\"px\": [^}]*\"u_dx\": [^}]*\\}, \"ae-arm\": \\{[^}]*\"u_dz\": [^}]*\\}, \"dual\": \\{[^}]*\"dx2\": [^}]*\"u_dx\": .*\"uncertainty\": \\{.*\"coverage_factor\": 2\\.0,.*\"draws\": 5,.*\"method\": \"Monte Carlo \\(GUM Supplement 1\\)\",.*\"interval_95\": \\[")

  add_test(NAME cli_predict_uncertainty_script
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DROOT=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_predict_uncertainty_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_predict_uncertainty_script PROPERTIES LABELS cli)
  return()
endif()

# ---- script mode ----
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(umachine ${ROOT}/machines/sample/machine-uncertainty.yaml)
set(plain ${ROOT}/machines/sample/machine.yaml)
set(program ${ROOT}/nc-samples/thesis-toolpath-2.ngc)

function(run out)
  execute_process(COMMAND ${ABBE} -q predict ${ARGN} -o ${WORK}/${out} RESULT_VARIABLE rc
                  ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "abbe predict ${ARGN}: exit ${rc}\n${err}")
  endif()
endfunction()

# The same seed gives the same bytes; another seed other u; the deviations
# are those of the plain prediction (the first ten columns and the line).
run(a.csv ${program} --machine ${umachine} --model dual --uncertainty 10 --seed 3)
run(b.csv ${program} --machine ${umachine} --model dual --uncertainty 10 --seed 3)
run(c.csv ${program} --machine ${umachine} --model dual --uncertainty 10 --seed 4)
run(plain.csv ${program} --machine ${umachine} --model dual)
file(SHA256 ${WORK}/a.csv ha)
file(SHA256 ${WORK}/b.csv hb)
file(SHA256 ${WORK}/c.csv hc)
if(NOT ha STREQUAL hb)
  message(FATAL_ERROR "the same seed gave different outputs")
endif()
if(ha STREQUAL hc)
  message(FATAL_ERROR "another seed gave the same output")
endif()
file(STRINGS ${WORK}/a.csv a_rows)
file(STRINGS ${WORK}/plain.csv p_rows)
list(LENGTH a_rows na)
list(LENGTH p_rows np)
if(NOT na EQUAL np)
  message(FATAL_ERROR "${na} rows with --uncertainty, ${np} without")
endif()
math(EXPR last "${na} - 1")
foreach(i RANGE 1 ${last})
  list(GET a_rows ${i} ra)
  list(GET p_rows ${i} rp)
  # plain: x..d (10), dx2..dz2 (3), line; uncertain: the same then u_dx,u_dy,u_dz before line.
  string(REGEX REPLACE ",[^,]*,[^,]*,[^,]*,([^,]*)$" ",\\1" ra_stripped "${ra}")
  if(NOT ra_stripped STREQUAL rp)
    message(FATAL_ERROR "row ${i}: '${ra}' is not the plain '${rp}' with u columns")
  endif()
endforeach()

# Errors: nothing to propagate (exit 1, naming the machine file and the
# field), too few draws and --align (usage, exit 2); the output is untouched.
file(WRITE ${WORK}/out.csv "previous contents\n")
include(${CMAKE_CURRENT_LIST_DIR}/lib/refusal_helpers.cmake)
function(expect code what pattern)
  refused_untouched(${code} "${what}" "${pattern}" ${WORK}/out.csv
                    ${ABBE} predict ${program} ${ARGN} -o ${WORK}/out.csv)
endfunction()
expect(1 "no uncertainty in the machine file"
       "machine.yaml \\[uncertainty\\]: error: --uncertainty: nothing to propagate"
       --machine ${plain} --uncertainty 10)
expect(2 "one draw" "--uncertainty" --machine ${umachine} --uncertainty 1)
expect(2 "--align datums without its datum sets" "--align datums needs --datum-primary"
       --machine ${umachine} --uncertainty 10 --align datums)
expect(2 "a datum set without --align datums" "--datum-primary needs --align datums"
       --machine ${umachine} --uncertainty 10 --align best-fit --datum-primary 2-31)

# With --align: the aligned columns, then u_dx,u_dy,u_dz, then u_adx,u_ady,
# u_adz; the absolute u are those without --align (the same draws), the
# deviations and aligned deviations those of plain --align.
run(al.csv ${program} --machine ${umachine} --uncertainty 10 --seed 3 --align best-fit)
run(u.csv ${program} --machine ${umachine} --uncertainty 10 --seed 3)
run(plain_al.csv ${program} --machine ${umachine} --align best-fit)
file(STRINGS ${WORK}/al.csv al_rows)
file(STRINGS ${WORK}/u.csv u_rows)
file(STRINGS ${WORK}/plain_al.csv pa_rows)
list(GET al_rows 0 header)
if(NOT header STREQUAL "x,y,z,px,py,pz,dx,dy,dz,d,adx,ady,adz,ad,u_dx,u_dy,u_dz,u_adx,u_ady,u_adz,line")
  message(FATAL_ERROR "--uncertainty --align header: ${header}")
endif()
list(LENGTH al_rows nal)
list(LENGTH pa_rows npa)
if(NOT nal EQUAL npa)
  message(FATAL_ERROR "${nal} rows with --uncertainty --align, ${npa} with --align")
endif()
math(EXPR last "${nal} - 1")
string(REPEAT "[^,]*," 10 f10)
string(REPEAT "[^,]*," 4 f4)
string(REPEAT "[^,]*," 3 f3)
foreach(i RANGE 1 ${last})
  list(GET al_rows ${i} r)
  list(GET u_rows ${i} ru)
  list(GET pa_rows ${i} rp)
  # x..d (10) and adx..ad (4), then u (3), u aligned (3), line.
  string(REGEX REPLACE "^(${f10})(${f4})(${f3})(${f3})([^,]*)$" "\\1\\2\\5" r_plain "${r}")
  string(REGEX REPLACE "^(${f10})(${f4})(${f3})(${f3})([^,]*)$" "\\1\\3\\5" r_u "${r}")
  if(NOT r_plain STREQUAL rp)
    message(FATAL_ERROR "row ${i}: '${r}' is not --align's '${rp}' with u columns")
  endif()
  if(NOT r_u STREQUAL ru)
    message(FATAL_ERROR "row ${i}: '${r}' does not carry the u of '${ru}'")
  endif()
endforeach()
