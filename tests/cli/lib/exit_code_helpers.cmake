# Helpers for script-mode tests that check exit codes (cmake -P):
# run(CODE COMMAND…) must exit with CODE; its stdout and stderr together in
# OUT (run_apart keeps them apart). expect(PATTERN WHAT): OUT must match the
# regular expression PATTERN.
# (lib/script_helpers.cmake has the variant for commands that must succeed.)
function(run expect_code)
  run_apart(${expect_code} ${ARGN})
  set(OUT "${OUT}${ERR}" PARENT_SCOPE)
endfunction()

# run_apart(CODE COMMAND…): as run, but stdout in OUT and stderr in ERR.
function(run_apart expect_code)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_code)
    message(FATAL_ERROR "expected exit ${expect_code}, got ${rc}: ${ARGN}\n${out}\n${err}")
  endif()
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
endfunction()

function(expect pattern what)
  if(NOT OUT MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: expected /${pattern}/ in:\n${OUT}")
  endif()
endfunction()
