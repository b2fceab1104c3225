# Tests of the Python module (tests/python/test_*.py, python3-pytest),
# registered when the module is built (-DABBE_PYTHON=ON). pytest's exit code
# 5 (no test collected) is a failure too. In a sanitized build the Python
# interpreter is not instrumented: the ASan runtime (and libstdc++) is
# preloaded and leak checking is off (the interpreter keeps its allocations
# at exit).
if(TARGET abbe_python)
  set(abbe_python_env "PYTHONPATH=${PROJECT_BINARY_DIR}/python" "ABBE_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                      "PYTHONDONTWRITEBYTECODE=1" "ABBE_EXE=$<TARGET_FILE:abbe>")
  if(ABBE_SANITIZE)
    # libstdc++ too: ASan must find the real __cxa_throw when it starts, or
    # the first C++ exception (abbe.InputError) aborts.
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libasan.so
                    OUTPUT_VARIABLE abbe_libasan OUTPUT_STRIP_TRAILING_WHITESPACE)
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libstdc++.so
                    OUTPUT_VARIABLE abbe_libstdcxx OUTPUT_STRIP_TRAILING_WHITESPACE)
    list(APPEND abbe_python_env "LD_PRELOAD=${abbe_libasan}:${abbe_libstdcxx}"
         "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1")
  endif()
  add_test(NAME python_module
           COMMAND ${ABBE_PYTHON_EXECUTABLE} -m pytest -q -p no:cacheprovider
                   ${PROJECT_SOURCE_DIR}/tests/python)
  set_tests_properties(python_module PROPERTIES
    LABELS python
    ENVIRONMENT "${abbe_python_env}"
    FAIL_REGULAR_EXPRESSION "no tests ran"
    TIMEOUT 300)
endif()
