# Command-level tests of `abbe simulate` (label cli), run with `cmake -P`:
# machine → files, campaign, measure (grid, program, effects), errors.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  include(${CMAKE_CURRENT_LIST_DIR}/lib/script_test.cmake)
  add_script_test(cli_simulate cli_simulate cli TIMEOUT 300)
  return()
endif()

include(${SRC}/tests/cli/lib/script_helpers.cmake)

file(REMOVE_RECURSE ${WORK})
run(${ABBE} -q simulate machine --seed 3 --like generic --spacing 50 -o ${WORK}/m)
foreach(f truth.yaml machine.yaml errors.csv runs.csv)
  if(NOT EXISTS ${WORK}/m/${f})
    message(FATAL_ERROR "simulate machine did not write ${f}")
  endif()
endforeach()
file(GLOB leftovers ${WORK}/m/*.tmp.*)
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()
run(${ABBE} iso230 ${WORK}/m/runs.csv --format json)
if(NOT run_out MATCHES "\"component\": \"EZZ\"")
  message(FATAL_ERROR "iso230 of the simulated runs lacks EZZ:\n${run_out}")
endif()

# Re-run the campaign noise-free at another spacing: the table has fwd = rev − reversal.
run(${ABBE} -q simulate campaign --truth ${WORK}/m/truth.yaml --spacing 100 --noise-scale 0
    -o ${WORK}/c)
file(STRINGS ${WORK}/c/errors.csv rows REGEX "^X,EXX,-990,")
list(LENGTH rows n)
if(NOT n EQUAL 2)
  message(FATAL_ERROR "campaign table: expected fwd and rev rows of X EXX at -990, got '${rows}'")
endif()

# Grid measurement with an injected reversal, noise-free, twice: identical files.
run(${ABBE} -q simulate measure --truth ${WORK}/m/truth.yaml --grid 200 --noise 0
    --inject reversal:Y:4um -o ${WORK}/grid1.csv)
run(${ABBE} -q simulate measure --truth ${WORK}/m/truth.yaml --grid 200 --noise 0
    --inject reversal:Y:4um -o ${WORK}/grid2.csv)
file(READ ${WORK}/grid1.csv g1)
file(READ ${WORK}/grid2.csv g2)
if(NOT g1 STREQUAL g2)
  message(FATAL_ERROR "the same measurement gave different files")
endif()
file(STRINGS ${WORK}/grid1.csv rows)
list(LENGTH rows n)
list(GET rows 0 header)
# 6 x-levels (−990 … 0 by 200, plus 0) × 4 y × 4 z + header
if(NOT header STREQUAL "x,y,z,dx,dy,dz,t,vx,vy,vz,nx,ny,nz,dn,tool_length,set" OR NOT n EQUAL 97)
  message(FATAL_ERROR "grid: header '${header}', ${n} rows")
endif()

# Along an NC program (tool 1 = 200 mm from the machine's tool table).
run(${ABBE} -q simulate measure --truth ${WORK}/m/truth.yaml
    --program ${SRC}/nc-samples/thesis-toolpath-1.ngc --noise 0.5um --seed 4 -o -)
if(NOT run_out MATCHES "\n-650\\.0000,-350\\.0000,-280\\.0000,[^\n]*,200,program\n")
  message(FATAL_ERROR "program measurement lacks the far corner:\n${run_out}")
endif()

# Squareness: the mazak profile carries the thesis' values as measured (no
# noise) into machine.yaml; --squareness-sigma adds noise to that measurement.
run(${ABBE} -q simulate machine --seed 7 --like mazak --spacing 100 -o ${WORK}/mz)
file(READ ${WORK}/mz/machine.yaml mz)
if(NOT mz MATCHES "EC0Y: 14\\.569\n  EB0Z: -24\\.362\n  EA0Z: 13\\.757\n")
  message(FATAL_ERROR "mazak machine.yaml lacks the thesis' squareness:\n${mz}")
endif()
run(${ABBE} -q simulate machine --seed 7 --like mazak --spacing 100 --squareness-sigma 2urad
    -o ${WORK}/mz2)
file(READ ${WORK}/mz2/machine.yaml mz2)
file(READ ${WORK}/mz2/truth.yaml mz2_truth)
if(mz2 MATCHES "EC0Y: 14\\.569\n" OR NOT mz2_truth MATCHES "squareness_sigma_urad: 2\n")
  message(FATAL_ERROR "--squareness-sigma 2urad did not add noise:\n${mz2}")
endif()
file(READ ${WORK}/mz/errors.csv t1)
file(READ ${WORK}/mz2/errors.csv t2)
if(NOT t1 STREQUAL t2)
  message(FATAL_ERROR "the squareness noise changed the laser tables")
endif()

# Bad input: exit code 1 and a message naming the problem.
foreach(bad -1 nan inf 2mrad)
  expect_failure("[--squareness-sigma]: error: expected a finite number ≥ 0 in µrad" ${ABBE}
                 simulate machine --squareness-sigma "${bad}" -o ${WORK}/x)
endforeach()
expect_failure("magnitude needs a unit" ${ABBE} simulate measure --truth ${WORK}/m/truth.yaml
               --grid 100 --inject reversal:Y:4)
expect_failure("give --grid SPACING, --box … or --program FILE" ${ABBE} simulate measure
               --truth ${WORK}/m/truth.yaml)
expect_failure("unknown machine profile" ${ABBE} simulate machine --like lathe -o ${WORK}/x)
file(WRITE ${WORK}/bad.yaml "abbe_truth: 1\nname: x\nchain: \"w X b X Z t\"\n")
expect_failure("bad.yaml:3:8 [chain]" ${ABBE} simulate measure --truth ${WORK}/bad.yaml --grid 100)
file(REMOVE_RECURSE ${WORK})
