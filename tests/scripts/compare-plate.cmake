# The plate comparison's dispersion measure (scripts/plate-dispersion.sh,
# issue 16 item 4): on hand-made histories with known arrival and shape errors,
# and a smoke run of scripts/compare-plate.sh on a coarse mesh (exact landing
# of the spring-free schemes, decrease under refinement; see the scripts).
# About 15 s on 2 cores. Included from tests/scripts/CMakeLists.txt.
add_test(NAME script.plate-dispersion-measure
  COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/plate-dispersion.sh ${PROJECT_SOURCE_DIR})
add_test(NAME script.compare-plate-smoke
  COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/compare-plate.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.plate-dispersion-measure PROPERTIES TIMEOUT 60 LABELS script)
set_tests_properties(script.compare-plate-smoke PROPERTIES TIMEOUT 600 LABELS script)
