# Script tests of the peer methods of the NBM on the bouncing plate: Nitsche
# (edp/bouncing-plate-nitsche.edp) and penalty (edp/bouncing-plate-penalty.edp),
# both implicit Newmark + semi-smooth Newton (edp/plate-newton.idp). They do not
# load the plugin, except the agreement test, which also runs the NBM example.
# Included from tests/scripts/CMakeLists.txt (uses NBM_RUN_FREEFEM, NBM_SCRIPT_OUT).
set(PEERS_EDP ${PROJECT_SOURCE_DIR}/edp)
set(PEERS_DIR ${CMAKE_CURRENT_LIST_DIR})

# NBM and Nitsche (theta = 1) converge towards each other: the L2(0,T)
# distances of y_com and of u_probe between their CSVs decrease at every mesh
# level (same dt, T covering the first impact and the rebound). About 25 s.
add_test(NAME script.plate-agreement-nbm-nitsche
  COMMAND bash ${PEERS_DIR}/plate-agreement.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
          "0.1 0.05 0.025" -dt 1e-4 -T 0.35
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.plate-agreement-nbm-nitsche PROPERTIES TIMEOUT 600 LABELS script)
# The same with the NBM on generalized-alpha (rhoInf = 0.6, method.md §5.4).
add_test(NAME script.plate-agreement-generalized-alpha
  COMMAND bash ${PEERS_DIR}/plate-agreement.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
          "0.1 0.05 0.025" -dt 1e-4 -T 0.35 -scheme generalized-alpha -rhoInf 0.6
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.plate-agreement-generalized-alpha PROPERTIES TIMEOUT 600 LABELS script)

# Each peer, P1 and P2, through the first impact and rebound: exit 0, outputs
# written, penetration printed (these methods penetrate; only finiteness is
# checked). Then Nitsche's incomplete and skew-symmetric variants (short runs).
function(peers_run_test name script)
  add_test(NAME script.plate-${name}
    COMMAND bash ${PEERS_DIR}/plate-peer-run.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
            ${PEERS_EDP}/${script} ${ARGN}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.plate-${name} PROPERTIES TIMEOUT 300 LABELS script)
endfunction()
peers_run_test(nitsche-P1 bouncing-plate-nitsche.edp -T 0.35)
peers_run_test(nitsche-P2 bouncing-plate-nitsche.edp -T 0.35 -order 2)
peers_run_test(penalty-P1 bouncing-plate-penalty.edp -T 0.35)
peers_run_test(penalty-P2 bouncing-plate-penalty.edp -T 0.35 -order 2)
peers_run_test(nitsche-theta0 bouncing-plate-nitsche.edp -T 0.2 -theta 0)
peers_run_test(nitsche-theta-1 bouncing-plate-nitsche.edp -T 0.2 -theta -1)

# Rejected inputs and the Newton iteration cap: exit code 1 with a clear message.
add_test(NAME script.plate-nitsche-theta2-rejected
  COMMAND bash ${PEERS_DIR}/expect-exit.sh 1 "-theta must be 1, 0 or -1, got '2'"
          ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PEERS_EDP}/bouncing-plate-nitsche.edp
          -theta 2 -out theta2
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
add_test(NAME script.plate-nitsche-theta-half-rejected
  COMMAND bash ${PEERS_DIR}/expect-exit.sh 1 "-theta must be 1, 0 or -1, got '0.5'"
          ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PEERS_EDP}/bouncing-plate-nitsche.edp
          -theta 0.5 -out theta-half
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
add_test(NAME script.plate-newton-cap
  COMMAND bash ${PEERS_DIR}/expect-exit.sh 1 "Newton did not converge in 1 iterations"
          ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PEERS_EDP}/bouncing-plate-penalty.edp
          -newtonMax 1 -T 0.2 -vtkFrames 0 -snapshots 0 -out newton-cap
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.plate-nitsche-theta2-rejected script.plate-nitsche-theta-half-rejected
  script.plate-newton-cap PROPERTIES TIMEOUT 120 LABELS script)
