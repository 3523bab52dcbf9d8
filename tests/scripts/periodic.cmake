# Script tests of the periodic-orbit API (issue: periodic solutions): the
# clamped plate example (edp/cantilever-plate-periodic.edp) with both mass
# treatments, checked on the summary line it prints.
set(NBM_CHECK_SUMMARY ${CMAKE_CURRENT_SOURCE_DIR}/periodic/check-summary.sh)
function(nbm_summary_test name checks script)
  add_test(NAME script.${name}
    COMMAND bash ${NBM_CHECK_SUMMARY} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${checks} ${script} ${ARGN}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.${name} PROPERTIES TIMEOUT 600 LABELS "script;periodic")
endfunction()
set(CANTILEVER ${PROJECT_SOURCE_DIR}/edp/cantilever-plate-periodic.edp)

# Massless boundary: shooting converges to a periodicity residual <= 1e-10,
# complementarity holds to 1e-12, the trivial Floquet multiplier is 1 to
# 1e-8, harmonic balance (H = 40) agrees on the period to 1e-6, the exact
# flow stays on the orbit for ten periods, the Newmark integrator
# (400 steps per period) drifts by less than 2% of the amplitude, and the
# 20 orbits of the continuation along the family are periodic to 1e-10.
nbm_summary_test(cantilever-periodic-massless
  "periodicity<=1e-10 complementarity<=1e-12 trivialMultiplier<=1e-8 periodDifference<=1e-6 switches>=2 contactTime>=1e-3 driftExact<=1e-9 driftNewmark<=0.02 familyPeriodicity<=1e-10"
  ${CANTILEVER} -out cantilever-massless -frames 2 -samples 20)
# Another parameter set: stiffer, thicker, finer mesh, larger gap.
nbm_summary_test(cantilever-periodic-massless-2
  "periodicity<=1e-10 complementarity<=1e-12 trivialMultiplier<=1e-8 periodDifference<=1e-6 switches>=2 driftExact<=1e-9 familyPeriodicity<=1e-10"
  ${CANTILEVER} -out cantilever-massless-2 -frames 2 -samples 20 -E 5000 -H 0.3 -lc 0.15 -gap 0.05 -tau 0.3 -harmonics 60)
# Paper NBM (mass on the contact nodes): accelerations jump at switches, so
# harmonic balance converges like 1/H: agreement to 1e-3 at H = 40.
nbm_summary_test(cantilever-periodic-consistent
  "periodicity<=1e-10 complementarity<=1e-12 periodDifference<=1e-3 switches>=2 driftExact<=1e-9 familyPeriodicity<=1e-10"
  ${CANTILEVER} -out cantilever-consistent -frames 2 -samples 20 -mass consistent -condition displacement -tau 0.3)

# Bad input of the periodic-orbit API: each call ends in an ExecError naming
# the argument (tests/scripts/periodic/orbit-cases.edp); the valid runs use
# every function, with and without a reduced basis.
set(NBM_ORBIT_CASES ${CMAKE_CURRENT_SOURCE_DIR}/periodic/orbit-cases.edp)
nbm_bad_valid(orbit-valid ${NBM_ORBIT_CASES} -case valid)
nbm_bad_valid(orbit-valid-modes ${NBM_ORBIT_CASES} -case valid-modes)
nbm_bad_valid(orbit-valid-continuation ${NBM_ORBIT_CASES} -case valid-continuation)
function(nbm_bad_orbit_case name regex)
  nbm_bad_input_test(orbit-${name} ${regex} ${NBM_ORBIT_CASES} -case ${name})
endfunction()
nbm_bad_orbit_case(modes [[nbmPeriodicOrbit: modes: expected >= 0]])
nbm_bad_orbit_case(modes-phase [[nbmPeriodicOrbit: phase: not available with modes > 0]])
nbm_bad_orbit_case(modes-range [[nbmPeriodicOrbit: modes: 1000.*expected 1 .. [0-9]+]])
nbm_bad_orbit_case(before-orbit [[nbmOrbitMultipliers: no periodic orbit computed yet]])
nbm_bad_orbit_case(u-size [[nbmPeriodicOrbit: u: size 5, expected]])
nbm_bad_orbit_case(F-size [[nbmPeriodicOrbit: F: size 5, expected]])
nbm_bad_orbit_case(u-nan [[nbmPeriodicOrbit: u: non-finite]])
nbm_bad_orbit_case(period [[nbmPeriodicOrbit: T: the period guess must be finite and > 0]])
nbm_bad_orbit_case(method [[nbmPeriodicOrbit: method: "newton".*expected]])
nbm_bad_orbit_case(condition [[nbmPeriodicOrbit: condition: "phase".*expected]])
nbm_bad_orbit_case(probe-range [[nbmPeriodicOrbit: probe: dof [0-9]+ out of range]])
nbm_bad_orbit_case(probe-fixed [[nbmPeriodicOrbit: probe: dof 0 is fixed]])
nbm_bad_orbit_case(phase-contact [[nbmPeriodicOrbit: phase: dof [0-9]+ is fixed or the normal component of a contact node]])
nbm_bad_orbit_case(phase-range [[nbmPeriodicOrbit: phase: dof -2 out of range \[0, [0-9]+\)]])
# probe = a contact dof is the reported amplitude's dof, as in every call.
nbm_bad_valid(orbit-valid-probe ${NBM_ORBIT_CASES} -case valid-probe)
nbm_bad_orbit_case(harmonics [[nbmPeriodicOrbit: harmonics: 0.*expected 1 .. 320]])
nbm_bad_orbit_case(integration [[nbmPeriodicOrbit: integration: "fft".*expected]])
nbm_bad_orbit_case(iterations [[nbmPeriodicOrbit: iterations: expected >= 1]])
nbm_bad_orbit_case(same-array [[nbmPeriodicOrbit: u and v must be different arrays]])
nbm_bad_orbit_case(no-convergence [[nbmPeriodicOrbit: shooting: no convergence in 2 Newton iterations]])
nbm_bad_orbit_case(harmonics-after-shooting [[nbmOrbitHarmonics: the last orbit was not computed by harmonic balance]])
nbm_bad_orbit_case(state-time [[nbmOrbitState: t: expected a time >= 0]])
nbm_bad_orbit_case(continue-first [[nbmContinueOrbit: needs the two last orbits of a family]])
nbm_bad_orbit_case(continue-step [[nbmContinueOrbit: step: expected a finite step > 0]])
nbm_bad_orbit_case(continue-harmonic-balance [[nbmContinueOrbit: continuation follows orbits computed by shooting]])
nbm_bad_orbit_case(continue-load [[nbmContinueOrbit: the two orbits were computed on different problems, loads]])
nbm_bad_orbit_case(unconstructed [[nbmPeriodicOrbit: the model was not constructed]])
nbm_bad_orbit_case(obstacle-moving [[nbmPeriodicOrbit: obstacle: plane through .* moves by its own law, which the periodic tools take only in a forced orbit]])
# A model with obstacle= in the periodic tools: the obstacle linearised at the
# reference configuration, the same orbits as the helpers' description of it
# (bit for bit), and in a forced orbit a moving one (a wall translating by
# two harmonics of the excitation, a circle whose radius changes) the same
# orbit as its gap harmonics given by hand (to 1e-9; measured 1e-14); a law
# that is not periodic with the excitation is refused.
nbm_bad_valid(orbit-valid-obstacle ${NBM_ORBIT_CASES} -case valid-obstacle)

# Backbones from grazing (edp/plate-backbone.edp, method.md §6): with the
# consistent mass the script computes the linear frequency of the plate's
# first mode itself (dense eigenproblem of the open system, LAPACK), and the
# backbone's first orbit (the grazing one, no contact) has it to 1e-8; with
# the massless boundary, 12 orbits periodic to 1e-10, the frequency 2% above
# the linear one at the last, which is in contact for 5% of its period.
set(PLATE_BACKBONE ${PROJECT_SOURCE_DIR}/edp/plate-backbone.edp)
nbm_summary_test(plate-backbone-linear
  "linearError<=1e-8 firstContactTime<=0 firstSwitches<=0 maxPeriodicity<=1e-10"
  ${PLATE_BACKBONE} -out plate-backbone-linear -mass consistent -points 1)
nbm_summary_test(plate-backbone
  "points>=12 maxPeriodicity<=1e-10 firstContactTime<=0 firstSwitches<=0 lastRatio>=1.02 lastSwitches>=4"
  ${PLATE_BACKBONE} -out plate-backbone -points 12)
# With the consistent mass (paper NBM) the first step along the linear family
# fails (the family leaves grazing with a vertical tangent) and the vertical
# start takes over (backbone.cpp, method.md §6): 12 orbits periodic to 1e-10,
# from the LAPACK frequency at grazing to 2% above it (measured 1.0248) with
# contact.
nbm_summary_test(plate-backbone-consistent
  "points>=12 linearError<=1e-8 maxPeriodicity<=1e-10 firstSwitches<=0 lastRatio>=1.02 lastSwitches>=2"
  ${PLATE_BACKBONE} -out plate-backbone-consistent -mass consistent -points 12)

# Bad input of nbmBackbone (tests/scripts/periodic/backbone-cases.edp).
set(NBM_BACKBONE_CASES ${CMAKE_CURRENT_SOURCE_DIR}/periodic/backbone-cases.edp)
nbm_bad_valid(backbone-valid ${NBM_BACKBONE_CASES} -case valid)
function(nbm_bad_backbone_case name regex)
  nbm_bad_input_test(backbone-${name} ${regex} ${NBM_BACKBONE_CASES} -case ${name})
endfunction()
nbm_bad_backbone_case(unconstructed [[nbmBackbone: the model was not constructed]])
nbm_bad_backbone_case(mode [[nbmBackbone: mode: 1000 out of range \[0, [0-9]+\)]])
nbm_bad_backbone_case(mode-negative [[nbmBackbone: mode: -1 out of range]])
nbm_bad_backbone_case(points [[nbmBackbone: points: expected >= 1, got 0]])
nbm_bad_backbone_case(step [[nbmBackbone: step: expected a finite step > 0]])
nbm_bad_backbone_case(energy [[nbmBackbone: energy: expected a limit > 0]])
nbm_bad_backbone_case(iterations [[nbmBackbone: iterations: expected >= 1]])
nbm_bad_backbone_case(modes [[nbmBackbone: modes: -3.*expected >= 0]])
nbm_bad_valid(backbone-valid-modes ${NBM_BACKBONE_CASES} -case valid-modes)
nbm_bad_valid(backbone-valid-frequency ${NBM_BACKBONE_CASES} -case valid-frequency)
nbm_bad_backbone_case(branch [[nbmBackbone: branch: "natural", expected "arclength" or "frequency"]])
nbm_bad_backbone_case(frequency-step [[nbmBackbone: frequencyStep: expected a finite relative step > 0, got 0]])
nbm_bad_backbone_case(energy-jump [[nbmBackbone: energyJump: expected a finite relative bound > 0, got -1]])
nbm_bad_backbone_case(skips [[nbmBackbone: skips: expected >= 0, got -1]])
nbm_bad_backbone_case(to [[nbmBackbone: to: expected a frequency > 0, got -1]])
nbm_bad_backbone_case(frequency-only [[nbmBackbone: frequencyStep: only with branch = "frequency"]])
nbm_bad_backbone_case(frequency-only-to [[nbmBackbone: to: only with branch = "frequency"]])
nbm_bad_backbone_case(F-size [[nbmBackbone: F: size 5, expected [0-9]+]])
nbm_bad_backbone_case(gap [[nbmBackbone: gaps: contact 0 has gap 0. a backbone from grazing needs every gap > 0]])
nbm_bad_backbone_case(load [[nbmBackbone: F: the static state under the load closes contact]])
nbm_bad_backbone_case(file [[nbmBackbone: cannot write /nonexistent-folder/backbone.csv]])
nbm_bad_backbone_case(probe-range [[nbmBackbone: probe: dof 100000 out of range \[0, [0-9]+\)]])
nbm_bad_backbone_case(probe-fixed [[nbmBackbone: probe: dof [0-9]+ is fixed]])

# Forced orbits (nbmForcedOrbit): valid calls and one broken input per case.
nbm_bad_valid(orbit-valid-forced ${NBM_ORBIT_CASES} -case valid-forced)
nbm_bad_orbit_case(forced-F0-size [[nbmForcedOrbit: F0: size 5, expected]])
nbm_bad_orbit_case(forced-Fc-rows [[nbmForcedOrbit: Fc \(harmonic 1\): size 5, expected]])
nbm_bad_orbit_case(forced-Fs-size [[nbmForcedOrbit: Fs \(harmonic 1\): size 5, expected]])
nbm_bad_orbit_case(forced-Fc-nan [[nbmForcedOrbit: Fc \(harmonic 2\): non-finite entries]])
nbm_bad_orbit_case(forced-gap-size [[nbmForcedOrbit: gapCos \(harmonic 1\): size [0-9]+, expected [0-9]+ \(one value per contact node\)]])
nbm_bad_orbit_case(forced-gap-nan [[nbmForcedOrbit: gapSin \(harmonic 2\): non-finite entries]])
nbm_bad_orbit_case(forced-no-harmonic [[nbmForcedOrbit: Fc, Fs, gapCos, gapSin: no harmonic]])
nbm_bad_orbit_case(forced-u-size [[nbmForcedOrbit: u: size 5, expected]])
nbm_bad_orbit_case(forced-omega-zero [[nbmForcedOrbit: omega: expected a finite excitation frequency > 0]])
nbm_bad_orbit_case(forced-omega-negative [[nbmForcedOrbit: omega: expected a finite excitation frequency > 0]])
nbm_bad_orbit_case(forced-omega-nan [[nbmForcedOrbit: omega: expected a finite excitation frequency > 0]])
nbm_bad_orbit_case(forced-subharmonic [[nbmForcedOrbit: subharmonic: expected m >= 1]])
nbm_bad_orbit_case(forced-rayleighM [[nbmForcedOrbit: rayleighM: -0.5.*expected a finite Rayleigh coefficient >= 0]])
nbm_bad_orbit_case(forced-rayleighK [[nbmForcedOrbit: rayleighK: .*nan.*expected a finite Rayleigh coefficient >= 0]])
nbm_bad_orbit_case(forced-probe-fixed [[nbmForcedOrbit: probe: dof 0 is fixed]])
nbm_bad_orbit_case(forced-probe-range [[nbmForcedOrbit: probe: dof [0-9]+ out of range]])
nbm_bad_orbit_case(forced-probe-negative [[nbmForcedOrbit: probe: dof -2 out of range]])
nbm_bad_orbit_case(forced-transient [[nbmForcedOrbit: transient: expected a number of periods >= 0]])
nbm_bad_orbit_case(forced-iterations [[nbmForcedOrbit: iterations: expected >= 1]])
nbm_bad_orbit_case(forced-same-array [[nbmForcedOrbit: u and v must be different arrays]])
nbm_bad_orbit_case(forced-modes [[nbmForcedOrbit: modes: -1.*expected >= 0 \(0: no reduced basis\)]])
nbm_bad_orbit_case(forced-modes-range [[nbmForcedResponse: modes: 100000.*expected 1 .. [0-9]+]])
nbm_bad_valid(orbit-valid-forced-modes ${NBM_ORBIT_CASES} -case valid-forced-modes)
nbm_bad_orbit_case(forced-no-convergence [[nbmForcedOrbit: forced orbit: no convergence in 1 Newton iteration]])
nbm_bad_valid(orbit-valid-forced-hbm ${NBM_ORBIT_CASES} -case valid-forced-hbm)
nbm_bad_orbit_case(forced-method [[nbmForcedOrbit: method: "newton".*expected "shooting" or "harmonic-balance"]])
nbm_bad_orbit_case(forced-harmonics [[nbmForcedOrbit: harmonics: 0.*expected m .. 320]])
nbm_bad_orbit_case(forced-harmonics-subharmonic [[nbmForcedOrbit: harmonics: 1.*expected m .. 320 \(m = 2]])
nbm_bad_orbit_case(forced-hbm-no-convergence [[nbmForcedOrbit: forced harmonic balance: no convergence in 1 Newton iteration]])
nbm_bad_orbit_case(forced-damping-matrix [[nbmForcedOrbit: damping: non-zero on the normal component of contact node 0]])
nbm_bad_orbit_case(forced-continue [[nbmContinueOrbit: continuation follows autonomous orbits]])
nbm_bad_orbit_case(forced-unconstructed [[nbmForcedOrbit: the model was not constructed]])
nbm_bad_valid(orbit-valid-response ${NBM_ORBIT_CASES} -case valid-response)
nbm_bad_orbit_case(select-none [[nbmSelectOrbit: no backbone or response curve computed yet]])
nbm_bad_orbit_case(select-range [[nbmSelectOrbit: k: point 3 out of range \[0, 3\)]])
nbm_bad_orbit_case(select-negative [[nbmSelectOrbit: k: point -1 out of range \[0, 3\)]])
nbm_bad_orbit_case(select-doubled [[nbmSelectOrbit: doubled: the last response curve has no period-doubled branch]])
nbm_bad_orbit_case(select-same-array [[nbmSelectOrbit: u and v must be different arrays]])
nbm_bad_orbit_case(response-parameter [[nbmForcedResponse: parameter: "force".*expected "omega" or "amplitude"]])
nbm_bad_orbit_case(response-to [[nbmForcedResponse: to: the end of the parameter range is required]])
nbm_bad_orbit_case(response-to-start [[nbmForcedResponse: to: expected a finite end of the omega range, other than the start]])
nbm_bad_orbit_case(response-from [[nbmForcedResponse: from: expected the other end of the omega range]])
nbm_bad_orbit_case(response-step [[nbmForcedResponse: step, maxStep: expected 0 < step <= maxStep]])
nbm_bad_orbit_case(response-points [[nbmForcedResponse: points: expected >= 1]])
nbm_bad_orbit_case(response-omega [[nbmForcedResponse: omega: expected a finite excitation frequency > 0]])
nbm_bad_orbit_case(response-gap-size [[nbmForcedResponse: gapCos \(harmonic 1\): size [0-9]+, expected [0-9]+ \(one value per contact node\)]])
nbm_bad_orbit_case(response-file [[nbmForcedResponse: file: cannot write /nonexistent-folder/curve.csv]])

# The forced plate (edp/forced-plate.edp). Linear limit: with the wall out of
# reach every orbit of the sweep (paper NBM, consistent mass) is the direct
# frequency response of the damped model solved in the script, to 1e-8.
set(FORCED_PLATE ${PROJECT_SOURCE_DIR}/edp/forced-plate.edp)
# The continuation through the linear resonance: every point's amplitude is
# the direct response's (to the 512-sample resolution of the extremes).
nbm_summary_test(forced-plate-linear
  "linearDifference<=1e-8 periodicity<=1e-10 contact<=0 unstable<=0 failed<=0 arcLinearDifference<=1e-4 arcContact<=0 arcUnstable<=0 folds<=0 arcEnd>=1.399"
  ${FORCED_PLATE} -out forced-linear -mass consistent -contactFree 1 -points 7 -down 0 -settle 0)
# With the wall in reach: the sweep finds stable orbits with contact; the
# damped Newmark stepper started 30% away from the stable contact orbit of
# fastest decay (largest |multiplier| about 0.91, so the transient is below
# 1e-5 after 120 periods) ends within 1e-3 of it at T/400, and closer at
# T/800 (what remains is the stepper's own error).
nbm_summary_test(forced-plate-settle
  "settleStart>=0.29 settleDistance<=1e-3 settleDistanceFine<=5e-4 settleRatio<=0.8 contact>=1 stable>=1 periodicity<=1e-10 complementarity<=1e-12"
  ${FORCED_PLATE} -out forced-settle -points 31 -down 0 -arclength 0)
# An assembled damping matrix (-dampedHalf: cd rho on the clamped half, not
# proportional to M or K; the state-space flow, method.md §9). Linear limit:
# the direct frequency response with the same matrix, to 1e-10. With the wall:
# the damped Newmark stepper (its own damping matrix code) settles on the
# stable contact orbit, closer at T/800 than at T/400. The continuation runs
# through both folds on the same flow.
nbm_summary_test(forced-plate-damping-matrix-linear
  "linearDifference<=1e-10 periodicity<=1e-10 contact<=0 failed<=0"
  ${FORCED_PLATE} -out forced-dmatrix-linear -mass consistent -contactFree 1 -points 5 -down 0 -settle 0 -arclength 0 -dampedHalf 3)
nbm_summary_test(forced-plate-damping-matrix-settle
  "settleStart>=0.29 settleDistance<=1e-3 settleDistanceFine<=3e-4 settleRatio<=0.5 contact>=1 stable>=1 periodicity<=1e-10"
  ${FORCED_PLATE} -out forced-dmatrix-settle -points 31 -down 0 -arclength 0 -dampedHalf 3)
nbm_summary_test(forced-plate-damping-matrix-curve
  "folds>=2 arcPeriodicity<=1e-10 arcEnd>=1.399 arcUnstable>=1 arcContact>=1"
  ${FORCED_PLATE} -out forced-dmatrix-curve -settle 0 -points 13 -down 0 -dampedHalf 3)

# The response curve by continuation in omega (nbmForcedResponse) against the
# sweeps, which know nothing of it: the two folds it finds lie within one
# sweep step (0.01) of where the sweeps jump (up: off the upper branch;
# down: onto it); every point periodic to 1e-10; the curve reaches its end.
# The backbone drawn over the curve (edp/forced-plate-backbone.idp): it
# starts at the linear frequency of the excited (longitudinal) mode, which
# the linear response of the sweeps peaks at to within their grid (0.01);
# its frequency branch (nbmBackbone, branch = "frequency") holds from
# grazing to beyond 1.2 (measured: 86 orbits to 1.219); and the curve leans
# on it: the backbone reaches the curve's peak amplitude within 0.005 of the
# peak's and the upper fold's frequencies (measured: 1.7e-3 and 3.4e-3).
nbm_summary_test(forced-plate-curve
  "folds>=2 foldCheckUp<=0.011 foldCheckDown<=0.011 arcPeriodicity<=1e-10 arcEnd>=1.399 arcUnstable>=1 periodicity<=1e-10 backboneLinearOffset<=0.006 backbonePoints>=40 branchHigh>=1.2 leanPeak<=0.005 leanFold<=0.005"
  ${FORCED_PLATE} -out forced-curve -settle 0)
# The 3D blade against its ovalised casing on the reduced model
# (edp/forced-blade-3d.edp; coarse meshes of geo/blade.geo, 2673 and 1965
# dofs): the response curve through its folds with stability and events;
# at its best-conditioned orbit with contact the full model's residual
# stays below 2e-3 (measured 4.7e-4, 3.3e-4), the 20-mode orbit lies within
# 3% of the 80-mode one (measured 0.97%, 0.86%), and the full model
# integrated by Newmark over one period from the reduced orbit's state comes
# back within 2% of it (0.68%, 0.81%: the reduction error, the same at
# twice the steps); the backbone's frequency branch gives at least 9 orbits
# (measured: 11, where it finds no orbit at the next four
# frequencies, 2.7% above the linear one; 12 of 12). The first also integrates
# the reduced model in time (NBM, modes = 20) from that orbit: after 100
# periods of 100 steps it is within 5e-3 of the orbit (measured 9.2e-4: the
# stable orbit kept), and over 10 periods the distance falls at an order
# >= 1.4 when the steps per period double (measured 1.66), and the full
# model's residual at its end state stays below 2e-3. About 75 and 30 s.
set(FORCED_BLADE ${PROJECT_SOURCE_DIR}/edp/forced-blade-3d.edp)
nbm_summary_test(forced-blade-3d
  "points>=40 folds>=1 grazing>=2 stable>=5 unstable>=1 checkResidual<=2e-3 modesDifference<=0.03 forcedFull<=0.02 backbone>=9 backboneEnergy>=1.1 reducedDrift<=5e-3 reducedOrder>=1.4 reducedResidual<=2e-3"
  ${FORCED_BLADE} -out forced-blade-3d -lcRoot 0.03 -lcTip 0.06 -points 40 -checkSteps 200 -vtkFrames 2 -backbonePoints 12
  -reducedPeriods 100)
nbm_summary_test(forced-blade-3d-2
  "points>=40 folds>=1 grazing>=2 stable>=5 unstable>=1 checkResidual<=2e-3 modesDifference<=0.03 forcedFull<=0.02 backbone>=12 backboneEnergy>=1.05"
  ${FORCED_BLADE} -out forced-blade-3d-2 -lcRoot 0.035 -lcTip 0.07 -W 0.25 -H 0.08 -E 2000 -nu 0.35
  -force 8 -gap 0.015 -delta 0.006 -points 40 -checkSteps 200 -vtkFrames 2 -backbonePoints 12
  -reducedPeriods 0)
# Shooting and harmonic balance agree on the curve (-hbmCheck): five orbits
# with contact on the upper branch, omega ratio 0.96 .. 1.16 (the last
# unstable), each found by shooting and recomputed by forced harmonic balance
# at H = 40 from it. The truncation measure of the series (the periodicity
# residual of the exact flow from its state) is 3.4e-4 .. 1.0e-3 there and
# the state difference tracks it (ratio 0.95 .. 1.1; amplitudes agree to
# 1.7e-6), so the bound is twice the largest truncation measure and the
# ratio must stay below 1.5; the stability of the two must agree everywhere.
# About 35 s of CPU.
nbm_summary_test(forced-plate-hbm
  "hbmPoints>=5 hbmContact>=5 hbmDifference<=2e-3 hbmStateOverPeriodicity<=1.5 hbmStabilityMismatch<=0"
  ${FORCED_PLATE} -out forced-hbm -points 0 -down 0 -arclength 0 -settle 0 -hbmCheck 5 -from 0.96 -to 1.16)

# The blade-tip interaction map (edp/blade-tip-sweep.edp): one point of it,
# the forced orbit against the ovalised casing (moving gaps, gapCos=) at
# Omega = 3.5, against a damped Newmark run of the same blade (nbmStep, the
# casing moved by nbmObstacle, T/400) from rest: after 150 periods (largest
# |multiplier| 0.93) the run is within 5e-3 of the orbit, relative to |u0|
# (measured 3.2e-3 at T/400, 7.7e-4 at T/800: the stepper's second-order
# error); the orbit rubs (switches) and is periodic to 1e-10.
nbm_summary_test(blade-tip-settle
  "settleStable>=1 settleSwitches>=2 settleStart>=0.99 settleDistance<=5e-3 periodicity<=1e-10 complementarity<=1e-12"
  ${PROJECT_SOURCE_DIR}/edp/blade-tip-sweep.edp -out blade-tip-settle -points 0 -settle 1
  -g0 1e-2 -delta 8e-3 -settleOmega 3.5 -settlePeriods 150 -settleSteps 400)
