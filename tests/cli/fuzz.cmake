# Short libFuzzer run (label "fuzz"): tests/fuzz/run_fuzz.sh builds the
# fuzz target with clang in its own build directory and runs it for 60 s on
# the seed corpus. Registered only when clang++ is installed; the script
# reports a skip (exit 77) if clang++ cannot link libFuzzer.
find_program(ABBE_FUZZ_CLANGXX NAMES clang++ clang++-19 clang++-18 clang++-17 clang++-16 clang++-15
                                     clang++-14)
if(ABBE_FUZZ_CLANGXX)
  add_test(NAME fuzz_program
           COMMAND ${CMAKE_CURRENT_LIST_DIR}/../fuzz/run_fuzz.sh ${PROJECT_SOURCE_DIR}
                   ${CMAKE_BINARY_DIR}/fuzz 60)
  set_tests_properties(fuzz_program PROPERTIES
    LABELS fuzz
    TIMEOUT 1800
    COST 800
    SKIP_RETURN_CODE 77
    ENVIRONMENT "ABBE_FUZZ_CXX=${ABBE_FUZZ_CLANGXX}")
else()
  message(STATUS "clang++ not found: the fuzz test (label fuzz) is not registered")
endif()

# A fuzz build has only the NC side of the library: configuring it with the
# tests (or Python, benchmarks, generators) in the same build directory is
# refused by name, before any compiler check.
add_test(NAME cmake_fuzz_build_alone
         COMMAND ${CMAKE_COMMAND} -S ${PROJECT_SOURCE_DIR}
                 -B ${CMAKE_BINARY_DIR}/fuzz_build_alone -G ${CMAKE_GENERATOR}
                 -DABBE_FUZZ=ON -DABBE_BUILD_TESTS=ON)
set_tests_properties(cmake_fuzz_build_alone PROPERTIES
  LABELS cli
  TIMEOUT 300
  PASS_REGULAR_EXPRESSION "ABBE_FUZZ builds the fuzz targets alone")
