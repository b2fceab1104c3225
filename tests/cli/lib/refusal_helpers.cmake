# refused_untouched(CODE WHAT PATTERN OUTPUT COMMAND…): the command exits with
# CODE, its stderr matches PATTERN, and OUTPUT still holds the
# "previous contents\n" the test wrote there (a refused run writes nothing).
function(refused_untouched code what pattern output)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
  if(NOT rc EQUAL ${code})
    message(FATAL_ERROR "${what}: expected exit code ${code}, got '${rc}'\n${err}")
  endif()
  if(NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: the error does not match '${pattern}':\n${err}")
  endif()
  file(READ ${output} contents)
  if(NOT contents STREQUAL "previous contents\n")
    message(FATAL_ERROR "${what}: the output was changed")
  endif()
endfunction()

# start_with_previous_output(OUTPUT): an empty WORK holding OUTPUT with the
# "previous contents\n" that refused_untouched looks for.
function(start_with_previous_output output)
  file(REMOVE_RECURSE ${WORK})
  file(MAKE_DIRECTORY ${WORK})
  file(WRITE ${output} "previous contents\n")
endfunction()

# expect_no_temporary_files(WHAT OUTPUT): no temporary file of the atomic
# writer (OUTPUT.tmp…) is left beside OUTPUT.
function(expect_no_temporary_files what output)
  file(GLOB leftovers ${output}.tmp*)
  if(leftovers)
    message(FATAL_ERROR "${what}: temporary files left behind: ${leftovers}")
  endif()
endfunction()
