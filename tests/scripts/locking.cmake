# ---- nearly incompressible bodies without locking (edp/locking-free.edp) ----
# docs/guide/nearly-incompressible.md. Static: plane strain against closed-form
# solutions valid up to nu = 1/2; the stiffness with a P0 pressure condensed
# out of P2 (P2/P0, the one a user gives the plugin) must stay within
# -maxError of the exact displacement for every nu on the finest mesh, while
# P1's displacement ratio at the largest nu must stay below -maxP1Ratio: it
# locks (the test shows the contrast, and fails if either side changes).
#  - cantilever, unstructured meshes n = 4, 8, 16, nu = 0.3 ... 0.4999: tip
#    deflection; measured P2/P0 within 0.0011 at n = 16, P1 0.696 at 0.4999.
#  - cylinder under internal pressure, mapped square mesh n = 16, nu = 0.4999:
#    inner radial displacement; measured P2/P0 within 0.00067, P1 0.488.
# Dynamic: the P2/P0 block, nu = 0.499, dropped onto the ground with the
# massless boundary, dt = 13 transit times of the pressure wave through an
# element, 500 steps: the energy never above its start by more than
# 1e-10 m g h0 (measured 1.3e-13), no penetration beyond 1e-12 h0 (measured 0).
set(LOCKING_EDP ${PROJECT_SOURCE_DIR}/edp/locking-free.edp)
nbm_script_test(locking-static-cantilever ${LOCKING_EDP} -part static -case cantilever
  -mesh delaunay -n 4 -levels 3 -maxError 0.005 -maxP1Ratio 0.8)
nbm_script_test(locking-static-cylinder ${LOCKING_EDP} -part static -case cylinder
  -mesh square -n 16 -levels 1 -nu 0.4999 -maxError 0.002 -maxP1Ratio 0.6)
nbm_script_test(locking-dynamic ${LOCKING_EDP} -part dynamic -nu 0.499 -n 8 -dt 2e-3 -T 1
  -maxRise 1e-10 -maxPenetration 1e-12)
foreach(name locking-static-cantilever locking-static-cylinder locking-dynamic)
  set_tests_properties(script.${name} PROPERTIES LABELS "script;locking")
endforeach()
