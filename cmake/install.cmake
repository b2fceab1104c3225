# install() rules of abbe: `cmake --install BUILD --prefix P` puts
#   P/bin/abbe, P/lib/libabbe_core.a, P/include/abbe/...,
#   P/lib/cmake/abbe/abbeConfig.cmake (+ version, targets) and
#   P/lib/pkgconfig/abbe.pc
# so that a project uses the library with `find_package(abbe)` and
# `target_link_libraries(app PRIVATE abbe::core)`, or with
# `pkg-config --cflags --libs abbe` (docs/library.md).
include(CMakePackageConfigHelpers)

set(ABBE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/abbe)

install(TARGETS abbe RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS abbe_core EXPORT abbeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/abbe DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(EXPORT abbeTargets NAMESPACE abbe:: DESTINATION ${ABBE_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/abbeConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/abbeConfig.cmake
                              INSTALL_DESTINATION ${ABBE_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/abbeConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/abbeConfig.cmake ${PROJECT_BINARY_DIR}/abbeConfigVersion.cmake
        DESTINATION ${ABBE_CMAKE_DIR})

# pkg-config: abbe_core is a static library, so its private dependencies
# (spdlog, yaml-cpp) are listed in Requires too; a sanitized build adds the
# sanitizer flags a program linking it needs.
set(ABBE_PC_SANITIZE "")
if(ABBE_SANITIZE)
  set(ABBE_PC_SANITIZE " -fsanitize=address,undefined")
endif()
# The prefix is found relative to the .pc file (cmake --install --prefix P
# may put it anywhere).
file(RELATIVE_PATH ABBE_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
configure_file(${PROJECT_SOURCE_DIR}/cmake/abbe.pc.in ${PROJECT_BINARY_DIR}/abbe.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/abbe.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
