# Registering a tests/cli/*.cmake file that runs itself in script mode
# (cmake -P). Included at configure time.
include_guard(GLOBAL)

# add_script_test(NAME WORKDIR LABELS [TIMEOUT SECONDS] [DEFINES -DVAR=VALUE…]):
# the test NAME runs the calling file with ABBE (the abbe executable), SRC
# (the source tree), WORK (WORKDIR in the build tree) and the DEFINES.
function(add_script_test name workdir labels)
  cmake_parse_arguments(PARSE_ARGV 3 arg "" "TIMEOUT" "DEFINES")
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DABBE=$<TARGET_FILE:abbe> -DSRC=${PROJECT_SOURCE_DIR}
                   ${arg_DEFINES} -DWORK=${CMAKE_CURRENT_BINARY_DIR}/${workdir}
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(${name} PROPERTIES LABELS "${labels}")
  if(arg_TIMEOUT)
    set_tests_properties(${name} PROPERTIES TIMEOUT ${arg_TIMEOUT})
  endif()
endfunction()
