# Helpers for the script-mode parts of tests/cli/*.cmake (cmake -P):
# run(COMMAND…) must exit 0 (its stdout in run_out; on failure both streams
# are shown, some commands print their diagnostics on stdout); expect_failure(MESSAGE
# COMMAND…) must exit 1 with MESSAGE on stderr.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN}: exit code ${rc}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

function(expect_failure expected_message)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "${ARGN}: exit code ${rc}, expected 1\n${err}")
  endif()
  string(FIND "${err}" "${expected_message}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${ARGN}: message lacks '${expected_message}':\n${err}")
  endif()
endfunction()

# expect_file_matches(FILE PATTERN WHAT): the text of FILE matches the
# regular expression PATTERN (WHAT and the text are shown if not).
function(expect_file_matches file pattern what)
  file(READ ${file} text)
  if(NOT text MATCHES "${pattern}")
    message(FATAL_ERROR "${what}:\n${text}")
  endif()
endfunction()
