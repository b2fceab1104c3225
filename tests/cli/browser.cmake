# Browser test of the HTML reports (label "browser"): renders them in headless
# Chromium and Firefox ESR (installed by tools/install-deps.sh, never by the
# test), checks the console and the DOM, drives the 3-D toolpath with mouse
# events (tests/browser/interaction.py) and keeps the screenshots in
# <build>/tests/browser/*.png. ABBE_SKIP_BROWSER=1 skips it (reported as
# skipped, as when chromium is not installed).
add_test(NAME browser_report
         COMMAND ${CMAKE_CURRENT_LIST_DIR}/../browser/run_browser_test.sh
                 $<TARGET_FILE:abbe> ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/browser)
set_tests_properties(browser_report PROPERTIES LABELS browser SKIP_RETURN_CODE 77 TIMEOUT 900)
