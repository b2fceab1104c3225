# Interoperability test against LinuxCNC's standalone interpreter rs274
# (Debian package linuxcnc-uspace, fetched once into the build tree).
# See docs/interop.md. ABBE_SKIP_INTEROP=1 skips it (reported as skipped).
add_executable(abbe_canon_compare ${CMAKE_CURRENT_SOURCE_DIR}/interop/canon_compare.cpp)
target_link_libraries(abbe_canon_compare PRIVATE abbe_warnings)

add_test(NAME interop_rs274
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/interop/run_interop.sh
                 $<TARGET_FILE:abbe> $<TARGET_FILE:abbe_canon_compare>
                 ${CMAKE_BINARY_DIR}/interop ${PROJECT_SOURCE_DIR})
set_tests_properties(interop_rs274 PROPERTIES LABELS interop SKIP_RETURN_CODE 77 TIMEOUT 1800)
