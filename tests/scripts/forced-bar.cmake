# The forced bar against a wall (edp/forced-bar.edp, issue 15 item 6),
# checked on its summary line (nbm_summary_test, periodic.cmake) against
# expectations the script computes independently of the continuation: the
# direct frequency response of the damped FE model (a complex saddle-point
# solve), the continuous bar's analytic response, the grazing roots of the
# linear response (bisection on the direct solve), the turns of omega along
# the curve at its folds; with -doubling 1, a period-2 orbit checked over T
# and 2T by the exact flow and by the Newmark stepper.
set(FORCED_BAR ${PROJECT_SOURCE_DIR}/edp/forced-bar.edp)
# Common to the runs with contact: contact-free orbits are the direct FE
# response to 1e-10 (states) and 2e-5 (amplitudes: extremes sampled 512
# times a period miss a sinusoid's by at most 1 - cos(pi / 512) = 1.9e-5); the grazings of the linear response are its roots to 1e-8 in
# omega (both found, none spurious); the folds lie where omega turns; points
# without contact are stable; the wall holds; every point periodic to 1e-10;
# the curve reaches its end.
set(FORCED_BAR_CHECKS "linearDifference<=1e-10 arcLinearDifference<=2e-5 \
grazingRoots>=2 linearGrazings<=2 grazingMatched>=2 grazingError<=1e-8 grazingAmplitudeError<=1e-7 \
folds>=2 foldCheck<=0.01 foldsWithoutTurn<=0 linearUnstable<=0 penetration<=1e-12 \
periodicity<=1e-10 arcEnd>=1.199")
# P1, N = 20, gap 0.1, aM = 0.02, bK = 0.002 (0.8% of critical): the curve
# has period doublings; branch switching at the first finds a period-2 orbit
# (periodic to 1e-10 over 2T, not over T: |u(T) - u(0)| / |u(0)| = 4.4e-3
# measured), confirmed by the Newmark stepper (T/4000) from its state:
# back within 1e-4 after 2T (4.8e-6 measured), not after T. FE against the
# continuous bar: 1.4e-2 measured near the resonance.
nbm_summary_test(forced-bar-p1
  "${FORCED_BAR_CHECKS} analyticDifference<=0.02 periodDoublings>=1 doubledPoints>=2 doubledPeriodicity<=1e-10 doubledSeparation>=1e-3 doubledNewmarkT>=1e-3 doubledNewmark2T<=1e-4"
  ${FORCED_BAR} -out forced-bar-p1 -doubling 1 -doublingAmplitude 0.05)
# P2, N = 10, gap 0.05, twice the damping (analytic: 8.8e-3 measured).
nbm_summary_test(forced-bar-p2
  "${FORCED_BAR_CHECKS} analyticDifference<=0.012"
  ${FORCED_BAR} -out forced-bar-p2 -order 2 -N 10 -gap 0.05 -aM 0.04 -bK 0.004)
# P1, N = 40, gap 0.05, twice the damping (analytic: 2.3e-4 measured).
nbm_summary_test(forced-bar-p1-fine
  "${FORCED_BAR_CHECKS} analyticDifference<=5e-4"
  ${FORCED_BAR} -out forced-bar-p1-fine -N 40 -gap 0.05 -aM 0.04 -bK 0.004)
# The paper's NBM (consistent mass) with the wall out of reach: the linear
# limit (its continuation stops at grazing, see the script's header).
nbm_summary_test(forced-bar-consistent-linear
  "linearDifference<=1e-10 arcLinearDifference<=2e-5 analyticDifference<=0.03 grazingRoots<=0 contact<=0 unstable<=0 folds<=0 arcEnd>=1.199"
  ${FORCED_BAR} -out forced-bar-consistent -mass consistent -gap 10)

# Bad input of branch switching (tests/scripts/bad-input/forced-doubling.edp).
set(NBM_DOUBLING_CASES ${CMAKE_CURRENT_SOURCE_DIR}/bad-input/forced-doubling.edp)
nbm_bad_valid(doubling-valid ${NBM_DOUBLING_CASES} -case valid-doubling)
nbm_bad_valid(doubling-valid-amplitude ${NBM_DOUBLING_CASES} -case valid-doubling-amplitude)
function(nbm_bad_doubling_case name regex)
  nbm_bad_input_test(${name} ${regex} ${NBM_DOUBLING_CASES} -case ${name})
endfunction()
nbm_bad_doubling_case(doubling-none [[nbmForcedResponse: doubling: no period doubling on the curve]])
nbm_bad_doubling_case(doubling-amplitude [[nbmForcedResponse: doublingAmplitude: expected a finite amplitude > 0.*got -1]])
nbm_bad_doubling_case(doubling-options [[nbmForcedResponse: doublingAmplitude, doubled, doubledFile: only with doubling = true]])
nbm_bad_doubling_case(doubling-file [[nbmForcedResponse: doubledFile: cannot write /nonexistent-folder/doubled.csv]])
nbm_bad_doubling_case(doubling-range [[nbmForcedResponse: doubling: the period-2 orbit was found at omega = [0-9.]+, outside the range]])
