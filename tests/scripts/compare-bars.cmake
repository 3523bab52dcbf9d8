# Smoke run of the bar comparison (scripts/compare-bars.sh, issue 16 item 3):
# every method on both exact bar solutions, P1, N = 20, 40, 80; convergence of
# each method, zero penetration of the NBM schemes, rates (see the script).
# About 1 minute on 2 cores. Included from tests/scripts/CMakeLists.txt.
add_test(NAME script.compare-bars-smoke
  COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/compare-bars.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.compare-bars-smoke PROPERTIES TIMEOUT 600 LABELS script)
