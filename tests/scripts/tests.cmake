# Script tests of the examples (FreeFem++ runs). Every example also checks
# impenetrability at every step and exits non-zero on a violation.
set(EDP ${PROJECT_SOURCE_DIR}/edp)
set(CONVERGENCE ${CMAKE_CURRENT_SOURCE_DIR}/convergence.sh)

nbm_script_test(exact-solutions ${CMAKE_CURRENT_SOURCE_DIR}/exact-solutions.edp)
# nbm.idp: contact descriptions of [Pk, Pk] (k = 1, 2, 3) and scalar bars
# against the geometry (counts, dof pairing, normals, gaps, inclined planes).
nbm_script_test(contact-helpers ${CMAKE_CURRENT_SOURCE_DIR}/contact-helpers.edp)

# Bouncing bar (benchmarks.md §A), reference data, dt = h/(k c): the relative
# L2(0,2T) error of u(0,t) decreases at every refinement and is <= 0.03 at N = 320.
foreach(order 1 2)
  add_test(NAME script.bouncing-bar-convergence-P${order}
    COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/bouncing-bar.edp
            errL2u0 0.03 "40 80 160 320" -order ${order}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.bouncing-bar-convergence-P${order} PROPERTIES TIMEOUT 1200 LABELS script)
endforeach()

# Another parameter set (k = tau_f/tau_w = 2), P3, and the explicit scheme.
add_test(NAME script.bouncing-bar-convergence-P3-k2
  COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/bouncing-bar.edp
          errL2u0 inf "20 40 80" -order 3 -L 5 -E 400 -rho 1 -grav 10 -h0 1.25
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
add_test(NAME script.bouncing-bar-convergence-explicit
  COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/bouncing-bar.edp
          errL2u0 inf "40 80 160" -order 1 -scheme explicit -L 10 -E 900 -rho 1 -grav 10 -h0 5 -dtFactor 0.5
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.bouncing-bar-convergence-P3-k2 script.bouncing-bar-convergence-explicit
  PROPERTIES TIMEOUT 1200 LABELS script)

# The massless boundary (mass = "redistributed") converges to the same solution.
add_test(NAME script.bouncing-bar-convergence-redistributed
  COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/bouncing-bar.edp
          errL2u0 inf "40 80 160" -order 1 -mass redistributed
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.bouncing-bar-convergence-redistributed PROPERTIES TIMEOUT 1200 LABELS script)

# Generalized-alpha (method.md §5.4): its default rhoInf = 0.8 meets Newmark's bound at
# N = 320 with the paper's NBM; HHT-alpha (rhoInf = 0.8) converges with the massless
# boundary on the parameter set k = 2.
add_test(NAME script.bouncing-bar-convergence-generalized-alpha
  COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/bouncing-bar.edp
          errL2u0 0.03 "40 80 160 320" -order 1 -scheme generalized-alpha
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
add_test(NAME script.bouncing-bar-convergence-hht-redistributed
  COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/bouncing-bar.edp
          errL2u0 0.06 "40 80 160" -order 1 -scheme hht-alpha -mass redistributed -L 5 -E 400 -rho 1 -grav 10 -h0 1.25
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.bouncing-bar-convergence-generalized-alpha
  script.bouncing-bar-convergence-hht-redistributed PROPERTIES TIMEOUT 1200 LABELS script)

# Clamped bar (benchmarks.md §B): the norms of the literature decrease.
foreach(order 1 2)
  add_test(NAME script.clamped-bar-convergence-P${order}
    COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/clamped-bar.edp
            L2L2u,LinfL2u,L2H1u,L2L2v,L2sigma inf "25 50 100 200" -order ${order}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.clamped-bar-convergence-P${order} PROPERTIES TIMEOUT 1200 LABELS script)
endforeach()

# The install step and the README's minimal example, from the installed files.
add_test(NAME script.installed-plugin
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/installed-plugin.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR})
set_tests_properties(script.installed-plugin PROPERTIES TIMEOUT 300 LABELS script)

# Clamped bar on another parameter set (L = 2, c = 2, a = 0.1): the scaled
# exact solution 2a U(x/L, c t/L) and the same norms.
add_test(NAME script.clamped-bar-convergence-P1-scaled
  COMMAND bash ${CONVERGENCE} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${EDP}/clamped-bar.edp
          L2L2u,LinfL2u,L2H1u,L2L2v,L2sigma inf "25 50 100" -order 1 -L 2 -E 4 -rho 1 -a 0.1
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.clamped-bar-convergence-P1-scaled PROPERTIES TIMEOUT 1200 LABELS script)

# Bouncing plate (NBM): free flight of the centre of mass, two parameter sets.
add_test(NAME script.plate-free-flight-P1
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/plate-free-flight.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} 10
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
add_test(NAME script.plate-free-flight-P2
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/plate-free-flight.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} 9.81
          -order 2 -E 5000 -nu 0.2 -rho 2 -width 0.8 -height 0.3 -lc 0.05 -dt 5e-4
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.plate-free-flight-P1 script.plate-free-flight-P2 PROPERTIES TIMEOUT 300 LABELS script)

# Chattering counts: the metrics script on a known history, and the bar's
# impacts (exactly one contact interval each, both mass treatments).
add_test(NAME script.chattering
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/chattering.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR})
set_tests_properties(script.chattering PROPERTIES TIMEOUT 300 LABELS script)

# Bouncing plate energy: the massless boundary's error vanishes with dt and is
# < 0.5% at the default dt; the paper NBM's loss per touch-down is reported.
add_test(NAME script.plate-energy
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/plate-energy.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.plate-energy PROPERTIES TIMEOUT 600 LABELS script)

# Damped bouncing plate (-rayleigh aM,bK): no penetration, D > 0, and with the
# massless boundary E + D = E(0) within 0.5% of m g h0.
add_test(NAME script.plate-damping
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/plate-damping.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR}
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(script.plate-damping PROPERTIES TIMEOUT 600 LABELS script)

# Exact restart (edp/restart.edp): saving after N steps and resuming, in the
# same process and in a new one, reproduces the uninterrupted run bit for bit,
# for every scheme and mass treatment and with either solver in one process;
# the disc and the inclined ground have rotated contact nodes (inexact round
# trip through user coordinates).
# nbm_restart_test(<variant> <labels>): variant = "name;restart.edp args...".
function(nbm_restart_test variant labels)
  list(POP_FRONT variant name)
  add_test(NAME script.restart-${name}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/restart.sh ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${variant}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.restart-${name} PROPERTIES TIMEOUT 300 LABELS "${labels}")
endfunction()
foreach(variant
    "newmark;-scheme;newmark"
    "explicit;-scheme;explicit"
    "moreau-jean;-scheme;moreau-jean;-restitution;0.5"
    "redistributed;-mass;redistributed"
    "disc-P2;-geo;${PROJECT_SOURCE_DIR}/geo/disc.geo;-order;2"
    "slope-redistributed;-slope;0.1;-h0;0.2;-mass;redistributed"
    "damped-newmark;-rayleighM;2;-rayleighK;1e-4"
    "damped-redistributed;-mass;redistributed;-rayleighM;2;-rayleighK;1e-4"
    "damped-explicit;-scheme;explicit;-rayleighM;2"
    "damped-moreau-jean;-scheme;moreau-jean;-restitution;0.5;-rayleighM;2;-rayleighK;1e-4"
    "mumps;-solver;mumps"
    "mumps-redistributed;-solver;mumps;-mass;redistributed")
  nbm_restart_test("${variant}" script)
endforeach()

# Long run, shortened (tests/long-run.sh; --full for 10^6 bar steps): no NaN,
# impenetrability, energy bounded where claimed, resident memory growing by
# less than 1% between the first and the last tenth of each run.
add_test(NAME script.long-run
  COMMAND bash ${PROJECT_SOURCE_DIR}/tests/long-run.sh --build ${CMAKE_BINARY_DIR})
set_tests_properties(script.long-run PROPERTIES TIMEOUT 900 LABELS "script;long-run")
