# Command-level tests of `abbe identify` (label cli): the dual-number paper's
# phantom data (tests/data/identify, generated from known parameters
# a = 12, b = −8, c = 5 µm/m, f1 … h3 = 30, −20, 15, −25, 18, −12, 22, −16,
# 9 µrad/m on the machine paper.yaml), the paper's degenerate line, the
# table fit through to `abbe predict`, and bad input.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(ABBE_IDENT_DATA ${CMAKE_CURRENT_SOURCE_DIR}/data/identify)

  # add_paper_identify_test(NAME MEASURED PASS): `abbe identify` of
  # MEASURED (in tests/data/identify) on paper.yaml; its output matches PASS.
  function(add_paper_identify_test name measured pass)
    add_test(NAME ${name}
             COMMAND $<TARGET_FILE:abbe> identify --measured ${ABBE_IDENT_DATA}/${measured}
                     --machine ${ABBE_IDENT_DATA}/paper.yaml)
    set_tests_properties(${name} PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "${pass}")
  endfunction()

  # Noise-free 150 × 100 × 100 mm grid at (300, 200, −200): all 12 back.
  add_paper_identify_test(cli_identify_paper_grid paper-grid.csv
    "  a +12\\.00000 ± 0\\.00000 +um/m\n(  [a-h][0-9]? .*\n)*  h3 +9\\.00000 ± 0\\.00000 +urad/m\n  rank 12/12, condition number [0-9.]+ ")

  # The paper's x = 1…15, y = z = 5: the y/z parameters are not identifiable.
  add_paper_identify_test(cli_identify_paper_line paper-line.csv
    "  a +12\\.00000 ± 0\\.00000 +um/m\n  b .*NOT IDENTIFIABLE\n(.*\n)*  rank [0-9]+/12, condition number inf(.*\n)*  unidentifiable combination")

  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_identify_workflow cli_identify cli TIMEOUT 300
                  DEFINES -DDATA=${ABBE_IDENT_DATA})
  return()
endif()

include(${SRC}/tests/cli/lib/script_helpers.cmake)


function(expect_match text regex what)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "${what}: no match for '${regex}' in:\n${text}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# Noisy grid (0.3 µm): JSON with rank, condition, standard errors.
run(${ABBE} identify --measured ${DATA}/paper-grid-noisy.csv --machine ${DATA}/paper.yaml
    -o ${WORK}/params.json)
file(READ ${WORK}/params.json js)
expect_match("${js}" "\"rank\": 12" "params.json")
expect_match("${js}" "\"name\": \"f1\",\n *\"stderr\": [0-9.e-]+" "params.json")
expect_match("${run_out}" "residual RMS 0\\.3[0-9]+ µm" "noisy grid summary")

# Tables: virtual machine grid → fitted component table → predict reads it.
run(${ABBE} simulate measure --truth ${SRC}/machines/sample/truth.yaml
    --box -800,-400,-500,-200,-100,-200 --grid 100 --noise 0.2um -o ${WORK}/grid.csv)
run(${ABBE} identify --measured ${WORK}/grid.csv --machine ${SRC}/machines/sample/machine.yaml
    --param tables --knots 100 --table-out ${WORK}/fitted.csv -o ${WORK}/tables.json)
expect_match("${run_out}" "residual RMS 0\\.[0-9]+ µm" "table fit summary")
expect_match("${run_out}" "\n  ECZ +no " "table fit separability")
file(READ ${SRC}/machines/sample/machine.yaml yaml)
string(REPLACE "table: errors.csv" "table: fitted.csv" yaml "${yaml}")
file(WRITE ${WORK}/fitted.yaml "${yaml}")
run(${ABBE} predict ${WORK}/grid.csv --points --machine ${WORK}/fitted.yaml --model ae-arm
    --summary-only)
expect_match("${run_out}" "ae-arm +all +[0-9]+ +[0-9.]+" "predict with the fitted table")

# Bad input: exit 1 with file and line or field.
expect_failure("no-such.csv" ${ABBE} identify --measured ${WORK}/no-such.csv
               --machine ${DATA}/paper.yaml)
file(WRITE ${WORK}/bad.csv "x,y,z,dx\n300,200,-200,1.0\n310,200,oops,1.0\n")
expect_failure("bad.csv:3" ${ABBE} identify --measured ${WORK}/bad.csv --machine ${DATA}/paper.yaml)
file(WRITE ${WORK}/nodev.csv "x,y,z,dx,nx,ny,nz,dn\n300,200,-200,,0,0,1,1.5\n")
expect_failure("nothing to identify" ${ABBE} identify --measured ${WORK}/nodev.csv
               --machine ${DATA}/paper.yaml)
expect_failure("--table-out needs --param tables" ${ABBE} identify
               --measured ${DATA}/paper-grid.csv --machine ${DATA}/paper.yaml
               --table-out ${WORK}/t.csv)
expect_failure("knot spacing" ${ABBE} identify --measured ${DATA}/paper-grid.csv
               --machine ${DATA}/paper.yaml --param tables --knots 0)
if(EXISTS ${WORK}/t.csv)
  message(FATAL_ERROR "a failed run left ${WORK}/t.csv behind")
endif()
