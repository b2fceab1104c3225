# Compensated programs a shop can run (issue 17): the provenance block and
# refusing a compensated program, bad numbers and ranges at file:line:col,
# verify failing what it cannot check, the machine's travel. Script mode.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli_compensate_shop
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/cli_compensate_shop_work
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(cli_compensate_shop PROPERTIES LABELS "cli;compensate")
  return()
endif()

set(MACHINE ${SRC}/machines/sample/machine.yaml)
set(TABLE ${SRC}/machines/sample/table.csv)
set(SAMPLE ${SRC}/nc-samples/thesis-toolpath-1.ngc)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

include(${SRC}/tests/cli/lib/exit_code_helpers.cmake)

# --- Provenance --------------------------------------------------------------
run(0 ${ABBE} compensate ${SAMPLE} --machine ${MACHINE} -o ${WORK}/c.ngc)
file(READ ${WORK}/c.ngc comp)
file(SHA256 ${MACHINE} machine_sha)
file(STRINGS ${MACHINE} table_line REGEX "^table:")
string(REGEX REPLACE "^table: *" "" table_name "${table_line}")
file(SHA256 ${SRC}/machines/sample/${table_name} table_sha)
foreach(p "^\\(abbe-compensated by abbe [0-9.]+: do not compensate this program again\\)\n"
          "\n\\(abbe machine-file sha256=${machine_sha} [^\n]*machine.yaml\\)\n"
          "\n\\(abbe table-file sha256=${table_sha} [^\n]*${table_name}\\)\n"
          "\n\\(abbe model ae-arm\\)\n" "\n\\(abbe tol 1 um step 5 mm min-segment 0.01 mm takeups micro\\)\n"
          "\n\\(abbe setup work offsets [^\n]*G54 X"
          "\n\\(abbe setup tool lengths, mm: without G43 130.0000, H1 200.0000"
          "\n\\(abbe setup start: tool tip at X0.0000 Y0.0000 Z-130.0000"
          "\n\\(abbe date 20[0-9][0-9]-[0-9][0-9]-[0-9][0-9]T[0-9:]+Z\\)\n")
  if(NOT comp MATCHES "${p}")
    message(FATAL_ERROR "provenance block: no /${p}/ in the compensated program")
  endif()
endforeach()
# SOURCE_DATE_EPOCH fixes the date (reproducible outputs).
set(ENV{SOURCE_DATE_EPOCH} 86400)
run(0 ${ABBE} compensate ${SAMPLE} --machine ${MACHINE} -o ${WORK}/c-epoch.ngc)
unset(ENV{SOURCE_DATE_EPOCH})
file(READ ${WORK}/c-epoch.ngc comp)
if(NOT comp MATCHES "\n\\(abbe date 1970-01-02T00:00:00Z\\)\n")
  message(FATAL_ERROR "SOURCE_DATE_EPOCH: the date is not 1970-01-02")
endif()
# A "%" first line stays first.
file(WRITE ${WORK}/pct.ngc "%\nG21 G90 G17\nG0 X-10 Y-10 Z-10\nG1 X-100 F500\nM2\n%\n")
run(0 ${ABBE} compensate ${WORK}/pct.ngc --machine ${MACHINE} -o ${WORK}/pct-c.ngc)
file(READ ${WORK}/pct-c.ngc comp)
if(NOT comp MATCHES "^%\n\\(abbe-compensated")
  message(FATAL_ERROR "%: the provenance block is not after the first line:\n${comp}")
endif()
# Compensating a compensated program: refused, no output.
run(1 ${ABBE} compensate ${WORK}/c.ngc --machine ${MACHINE} -o ${WORK}/cc.ngc)
expect("c.ngc:1:1: error: this program was already compensated by abbe" "compensated twice")
if(EXISTS ${WORK}/cc.ngc)
  message(FATAL_ERROR "compensated twice: an output was written")
endif()
# verify checks the machine files of the block: the same content passes,
# another content (one more comment line) is refused at the block.
run(0 ${ABBE} verify ${WORK}/c.ngc --against ${SAMPLE} --machine ${MACHINE} --check)
expect("compensated by abbe [0-9.]+ on 20" "verify names the provenance")
file(READ ${MACHINE} text)
file(WRITE ${WORK}/m2/machine.yaml "${text}# changed\n")
file(COPY ${SRC}/machines/sample/${table_name} DESTINATION ${WORK}/m2)
run(1 ${ABBE} verify ${WORK}/c.ngc --against ${SAMPLE} --machine ${WORK}/m2/machine.yaml --check)
expect("c.ngc:1: error: the program was compensated for machine-file .*machine.yaml" "other machine")

# --- Bad numbers and ranges: exit 1 at file:line:col, never 3 ---------------
file(WRITE ${WORK}/big.ngc "G21 G90\nG1 X99999999999999999999 F100\nM2\n")
foreach(cmd "path;-o;${WORK}/big.csv" "predict;-o;${WORK}/big.csv"
            "compensate;-o;${WORK}/big-c.ngc")
  run(1 ${ABBE} ${cmd} ${WORK}/big.ngc --machine ${MACHINE})
  expect("big.ngc:2:4: error: the motion reaches a coordinate of 1e\\+20 mm, beyond" "${cmd}")
endforeach()
file(WRITE ${WORK}/h.ngc "G21 G90\nG0 G43 H99999999999 Z-10\nM2\n")
run(1 ${ABBE} compensate ${WORK}/h.ngc --machine ${MACHINE} -o ${WORK}/h-c.ngc)
expect("h.ngc:2:8: error: H word \\(tool number\\) is above 99999" "G43 H")
file(WRITE ${WORK}/step.ngc "G21 G90\nG0 X-10 Y-10 Z-10\nG1 X-100 F500\nM2\n")
run(1 ${ABBE} compensate ${WORK}/step.ngc --machine ${MACHINE} --step 1e-9 -o ${WORK}/s-c.ngc)
expect("step.ngc:2:4: error: the .*motion of .* needs more than 1e9 points" "--step 1e-9")
run(1 ${ABBE} verify ${WORK}/step.ngc --against ${WORK}/step.ngc --machine ${MACHINE} --step 1e-9)
expect("step.ngc:2: error: the .*motion of .* needs more than 1e9 points" "verify --step 1e-9")
run(1 ${ABBE} predict ${WORK}/step.ngc --machine ${MACHINE} --step 1e-9 -o ${WORK}/s.csv)
expect("step.ngc:2:4: error: the .*motion of .* needs more than 1e9 points" "predict --step 1e-9")
# N beyond 2^63 with --renumber (was written as N-9223372036854775807).
file(WRITE ${WORK}/n.ngc
     "G21 G90\nG0 X-10 Y-10 Z-10\nN99999999999999999999 G1 X-900 Y-400 F500\nM2\n")
run(1 ${ABBE} compensate ${WORK}/n.ngc --machine ${MACHINE} --tol 0.05 --renumber
    -o ${WORK}/n-c.ngc)
expect("n.ngc:3:1: error: N[0-9]+ is too large to number" "--renumber N")
run(0 ${ABBE} compensate ${WORK}/n.ngc --machine ${MACHINE} --tol 0.05 -o ${WORK}/n-c.ngc)

# --- verify passes nothing it cannot check ------------------------------------
# A "compensated" program of a header and M2: no points, FAIL.
file(WRITE ${WORK}/empty.ngc "(abbe-compensated by abbe 0: do not compensate this program again)\nM2\n")
run(4 ${ABBE} verify ${WORK}/empty.ngc --against ${SAMPLE} --machine ${MACHINE} --check)
expect("FAIL: the compensated program has no feed points" "header and M2")
expect("have no feed motion of the compensated program to match" "header and M2")
# Feed moves on one side only.
file(WRITE ${WORK}/rapids.ngc "G21 G90\nG0 X-10 Y-10 Z-10\nG0 X-100\nM2\n")
run(4 ${ABBE} verify ${WORK}/c.ngc --against ${WORK}/rapids.ngc --machine ${MACHINE} --check)
expect("FAIL: the original program has no feed points" "original without feeds")
# A pipe (read once): the same points as from the file.
run(0 ${ABBE} verify ${WORK}/c.ngc --against ${SAMPLE} --machine ${MACHINE} --check)
string(REGEX MATCHALL "[0-9]+ points" file_points "${OUT}")
execute_process(COMMAND bash -c "\"$0\" verify <(cat \"$1\") --against <(cat \"$2\") --machine \"$3\" --check"
                        ${ABBE} ${WORK}/c.ngc ${SAMPLE} ${MACHINE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE OUT ERROR_VARIABLE err)
string(REGEX MATCHALL "[0-9]+ points" pipe_points "${OUT}")
if(NOT rc EQUAL 0 OR NOT pipe_points STREQUAL file_points)
  message(FATAL_ERROR "verify from pipes: exit ${rc}, ${pipe_points} (file: ${file_points})\n${OUT}${err}")
endif()

# --- Travel --------------------------------------------------------------------
# X to -2000 on a 990 mm axis: compensate refuses, predict warns (points per axis).
file(WRITE ${WORK}/far.ngc "G21 G90\nG0 X-10 Y-10 Z-10\nG1 X-2000 F500\nG1 Y-20\nM2\n")
run(1 ${ABBE} compensate ${WORK}/far.ngc --machine ${MACHINE} -o ${WORK}/far-c.ngc)
expect("far.ngc:3: error: the point .* is outside the machine's travel: X axis at -[0-9.]+ mm, travel \\[-990, 0\\]"
       "compensate outside the travel")
run(0 ${ABBE} compensate ${WORK}/far.ngc --machine ${MACHINE} --allow-outside-travel
    -o ${WORK}/far-c.ngc)
expect("warning: [0-9]+ of [0-9]+ points outside the travel \\(points per axis: X [0-9]+\\), first on lines 3, 4"
       "--allow-outside-travel")
run(0 ${ABBE} predict ${WORK}/far.ngc --machine ${MACHINE} -o ${WORK}/far.csv)
expect("far.ngc: [0-9]+ of [0-9]+ points outside the travel \\(points per axis: X [0-9]+\\), first on lines 3, 4"
       "predict outside the travel")
# Inside the travel: no warning.
run(0 ${ABBE} predict ${SAMPLE} --machine ${MACHINE} -o ${WORK}/in.csv)
if(OUT MATCHES "outside the travel")
  message(FATAL_ERROR "predict inside the travel warns:\n${OUT}")
endif()

# --- Setup ------------------------------------------------------------------------
# Before the program sets Z (and G43), the first rapid gets no Z word: its
# position rests on the assumed start at machine home.
file(WRITE ${WORK}/setup.ngc "G21 G90 G17\nG0 X-10 Y-10\nG43 H1 Z-250\nG1 X-100 F500\nG1 Y-100\nM2\n")
run(0 ${ABBE} compensate ${WORK}/setup.ngc --machine ${MACHINE} -o ${WORK}/setup-c.ngc)
file(STRINGS ${WORK}/setup-c.ngc body REGEX "^[^(]")
list(GET body 1 first_rapid)
if(first_rapid MATCHES "Z")
  message(FATAL_ERROR "a Z word before the program set Z: ${first_rapid}")
endif()
list(GET body 2 g43)
if(NOT g43 MATCHES "^G43 H1 Z-2(49|50)\\.[0-9]+")
  message(FATAL_ERROR "the G43 block does not carry the Z correction: ${g43}")
endif()
# --tool, --tool-length and --work-offset on compensate, verify and predict.
run(0 ${ABBE} compensate ${WORK}/setup.ngc --machine ${MACHINE} --tool 1=150 --tool-length 100
    --work-offset G54=-1,-2,-3 -o ${WORK}/setup-t.ngc)
file(READ ${WORK}/setup-t.ngc comp)
foreach(p "without G43 100.0000, H1 150.0000" "G54 X-1.0000 Y-2.0000 Z-3.0000"
          "start: tool tip at X0.0000 Y0.0000 Z-100.0000")
  if(NOT comp MATCHES "${p}")
    message(FATAL_ERROR "setup options: no '${p}' in the provenance block")
  endif()
endforeach()
run(0 ${ABBE} verify ${WORK}/setup-t.ngc --against ${WORK}/setup.ngc --machine ${MACHINE}
    --tool 1=150 --tool-length 100 --work-offset G54=-1,-2,-3 --check)
run(1 ${ABBE} verify ${WORK}/setup-t.ngc --against ${WORK}/setup.ngc --machine ${MACHINE} --check)
expect("setup-t.ngc:1: error: the program was compensated for the setup \"work offsets" "setup")
run(0 ${ABBE} predict ${WORK}/setup.ngc --machine ${MACHINE} -o ${WORK}/p1.csv)
run(0 ${ABBE} predict ${WORK}/setup.ngc --machine ${MACHINE} --work-offset G54=-1,-2,-3
    -o ${WORK}/p2.csv)
file(SHA256 ${WORK}/p1.csv h1)
file(SHA256 ${WORK}/p2.csv h2)
if(h1 STREQUAL h2)
  message(FATAL_ERROR "predict --work-offset changed nothing")
endif()
run(1 ${ABBE} predict ${WORK}/setup.ngc --machine ${MACHINE} --tool 1=x -o ${WORK}/p3.csv)
expect("--tool" "predict --tool 1=x")

# --- Duplicate keys in a machine file ---------------------------------------------
file(MAKE_DIRECTORY ${WORK}/m3)
file(COPY ${SRC}/machines/sample/${table_name} DESTINATION ${WORK}/m3)
file(READ ${MACHINE} text)
file(WRITE ${WORK}/m3/machine.yaml "${text}tool_length: 50\n")
run(1 ${ABBE} predict ${SAMPLE} --machine ${WORK}/m3/machine.yaml -o ${WORK}/d.csv)
expect("machine.yaml:[0-9]+:1 \\[tool_length\\]: error: duplicate key `tool_length` \\(first on line 7\\)"
       "duplicate tool_length")
string(REPLACE "tool_table:\n  1: 200" "tool_table:\n  1: 200\n  1: 300" text2 "${text}")
file(WRITE ${WORK}/m3/machine.yaml "${text2}")
run(1 ${ABBE} compensate ${SAMPLE} --machine ${WORK}/m3/machine.yaml -o ${WORK}/d.ngc)
expect("machine.yaml:10:3 \\[tool_table.1\\]: error: duplicate key `1` \\(first on line 9\\)"
       "duplicate tool-table entry")

# --- Signals: an interrupted run leaves no OUT.tmp.XXXXXX ---------------------------
# The program comes from a FIFO whose writer stays open: the command waits
# for input with its temporary output created (waited for up to 10 s: a
# loaded machine may take more than a second to start it), and is signalled there.
file(MAKE_DIRECTORY ${WORK}/sig)
foreach(cmd "compensate" "path" "predict")
  foreach(sig INT TERM)
    file(REMOVE ${WORK}/sig/fifo)
    execute_process(
      COMMAND bash -c "set -m; mkfifo \"$1/fifo\"; (printf 'G21 G90\\nG0 X-10 Y-10 Z-10\\nG1 X-100 F500\\n'; sleep 30) >\"$1/fifo\" & w=$!; \"$0\" ${cmd} \"$1/fifo\" --machine \"$2\" -o \"$1/out.txt\" >/dev/null 2>&1 & pid=$!; for i in $(seq 100); do ls \"$1\" | grep -q 'out.txt.tmp' && break; sleep 0.1; done; ls \"$1\" | grep -c 'out.txt.tmp'; kill -${sig} $pid; wait $pid; rc=$?; kill -- -$w; echo rc=$rc"
              ${ABBE} ${WORK}/sig ${MACHINE}
      OUTPUT_VARIABLE out)
    file(GLOB left ${WORK}/sig/out.txt*)
    if(NOT out MATCHES "^1\nrc=(130|143)" OR left)
      message(FATAL_ERROR "${cmd}, SIG${sig}: ${out}, left: ${left}")
    endif()
  endforeach()
endforeach()

message(STATUS "compensate shop cases: all passed")
