# Interoperability test against LinuxCNC's standalone interpreter rs274
# (Debian package linuxcnc-uspace, unpacked by tools/install-deps.sh --test).
# See docs/interop.md. ABBE_SKIP_INTEROP=1 skips it (reported as skipped).
add_executable(abbe_canon_compare ${CMAKE_CURRENT_SOURCE_DIR}/interop/canon_compare.cpp)
target_link_libraries(abbe_canon_compare PRIVATE abbe_warnings)
add_executable(abbe_random_programs ${CMAKE_CURRENT_SOURCE_DIR}/interop/random_programs.cpp)
target_link_libraries(abbe_random_programs PRIVATE abbe_warnings)

add_test(NAME interop_rs274
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/interop/run_interop.sh
                 $<TARGET_FILE:abbe> $<TARGET_FILE:abbe_canon_compare>
                 ${CMAKE_BINARY_DIR}/interop ${PROJECT_SOURCE_DIR}
                 $<TARGET_FILE:abbe_random_programs>
                 $<TARGET_FILE:abbe_compensated_compare> $<TARGET_FILE:gen_program>
                 $<TARGET_FILE:gen_flow_programs>)
# COST: about five minutes under the sanitizers; ctest starts it among the
# long sweeps on a fresh build rather than last, where it ran alone.
set_tests_properties(interop_rs274 PROPERTIES LABELS interop SKIP_RETURN_CODE 77 TIMEOUT 1800
                                              COST 600)

# `abbe interpret` summary mode (the interpret-only mode of the benchmarks).
add_test(NAME interpret_summary
         COMMAND abbe interpret ${CMAKE_CURRENT_SOURCE_DIR}/interop/ncfiles/cycles.ngc)
set_tests_properties(interpret_summary PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "^lines=45 motions=212 rapid=[0-9]+ linear=[0-9]+ arc=0 dwell=[0-9]+")
add_test(NAME interpret_refuses_bad_input
         COMMAND sh -c "\"$1\" interpret \"$2\"; echo exit=$?" sh $<TARGET_FILE:abbe>
                 ${CMAKE_CURRENT_SOURCE_DIR}/data/bad/cutter-comp-g41.nc)
set_tests_properties(interpret_refuses_bad_input PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "cutter-comp-g41.nc:3:1: error: cutter radius compensation \\(G41\\) without a D word.*exit=1")

# Compensated programs in rs274 (tests/interop/run_interop.sh, docs/interop.md).
add_executable(abbe_compensated_compare ${CMAKE_CURRENT_SOURCE_DIR}/interop/compensated_compare.cpp)
target_link_libraries(abbe_compensated_compare PRIVATE abbe_core abbe_warnings)
