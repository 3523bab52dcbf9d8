# Bad-input tests (included from tests/scripts/CMakeLists.txt): each case breaks
# one input of a valid problem; the plugin must stop with an ExecError whose
# message names the faulty argument and what was expected.
#   cases.edp -case <name>: the 1D bar of setup.idp
#   plane.edp -case <name>: a 2D elastic square on a plane (nbmContactPlane)
# The `valid-*` runs check that the unbroken setups succeed, so that each
# failure below comes from the one broken input. Regexes are grep -E patterns;
# bracket arguments keep CMake from reading their backslashes.
set(NBM_BAD_DIR ${CMAKE_CURRENT_SOURCE_DIR}/bad-input)

function(nbm_bad_case name regex)
  nbm_bad_input_test(${name} ${regex} ${NBM_BAD_DIR}/cases.edp -case ${name})
endfunction()
function(nbm_bad_plane_case name regex)
  nbm_bad_input_test(plane-${name} ${regex} ${NBM_BAD_DIR}/plane.edp -case ${name} ${ARGN})
endfunction()
function(nbm_bad_valid name script)
  add_test(NAME bad-input.${name}
    COMMAND bash ${NBM_RUN_FREEFEM} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${script} ${ARGN}
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(bad-input.${name} PROPERTIES TIMEOUT 300 LABELS bad-input)
endfunction()

nbm_bad_valid(valid-newmark ${NBM_BAD_DIR}/cases.edp -case valid-newmark)
nbm_bad_valid(valid-explicit ${NBM_BAD_DIR}/cases.edp -case valid-explicit)
nbm_bad_valid(valid-redistributed ${NBM_BAD_DIR}/cases.edp -case valid-redistributed)
nbm_bad_valid(valid-moreau-jean ${NBM_BAD_DIR}/cases.edp -case valid-moreau-jean)
nbm_bad_valid(valid-damping ${NBM_BAD_DIR}/cases.edp -case valid-damping)
nbm_bad_valid(valid-restart ${NBM_BAD_DIR}/cases.edp -case valid-restart)
nbm_bad_valid(valid-replace ${NBM_BAD_DIR}/cases.edp -case valid-replace)
nbm_bad_valid(valid-tgv ${NBM_BAD_DIR}/cases.edp -case valid-tgv)
nbm_bad_valid(plane-valid-newmark ${NBM_BAD_DIR}/plane.edp -case valid-newmark)
nbm_bad_valid(plane-valid-explicit ${NBM_BAD_DIR}/plane.edp -case valid-explicit)

# ---- construction: matrices ----
nbm_bad_case(m-k-size [=[NBM: M: size 21x21 differs from the size of K, 11x11]=])
nbm_bad_case(k-nonsymmetric [=[NBM: K: not symmetric at \([0-9]+, [0-9]+\). expected a symmetric matrix]=])
nbm_bad_case(k-nan [=[NBM: K: non-finite entry at \([0-9]+, [0-9]+\)]=])
nbm_bad_case(k-unassembled [=[NBM: matrix K is empty or not an assembled sparse matrix]=])
nbm_bad_case(k-nonsquare [=[NBM: (K: 21x11 is not square|M: size 11x11 differs from the size of K, 21x11)]=])
nbm_bad_case(mk-nonsquare [=[NBM: (M|K): 21x11 is not square]=])
nbm_bad_case(k-tgv-minus1 [=[NBM: K: .*(symmetric|tgv|Dirichlet)]=])
nbm_bad_case(k-tgv-minus2 [=[NBM: K: .*(tgv|Dirichlet)]=])
nbm_bad_case(singular-contact-block [=[NBM: K: the contact block K_CC is not positive definite]=])
nbm_bad_case(mass-zero [=[NBM: M[ :].*not positive definite]=])
nbm_bad_case(mass-negative [=[NBM: M[ :].*not positive definite]=])

# ---- construction: contact description ----
nbm_bad_case(cdof-out-of-range [=[NBM: contact dofs: index 11 of contact node 0 outside \[0, 11\)]=])
nbm_bad_case(cdof-negative [=[NBM: contact dofs: index -1 of contact node 0 outside \[0, 11\)]=])
nbm_bad_case(cdof-duplicate [=[NBM: contact dofs: dof 0 appears twice]=])
nbm_bad_case(cdof-fixed [=[NBM: contact dofs: dof 0 of contact node 0 is also a fixed \(Dirichlet\) dof]=])
nbm_bad_case(cdof-tgv [=[NBM: contact dofs: dof 0 of contact node 0 is also a fixed \(Dirichlet\) dof]=])
nbm_bad_case(dofs-not-multiple [=[NBM: contact dofs: 3 entries is not a multiple of the number of gaps \(2\)]=])
nbm_bad_case(empty-contact [=[NBM: contact set is empty: expected at least one contact node]=])
nbm_bad_case(dofs-per-node [=[NBM: contact dofs: 4 dofs per contact node, expected 1, 2 or 3]=])
nbm_bad_case(normals-size [=[NBM: normals: size 2, expected 1 ]=])
nbm_bad_case(normal-zero [=[NBM: normals: contact node 0 has \|n\| = 0(\.0*)?, expected a unit vector]=])
nbm_bad_case(normal-non-unit [=[NBM: normals: contact node 0 has \|n\| = 2(\.0*)?, expected a unit vector]=])
nbm_bad_case(normal-nan [=[NBM: normals: non-finite component at contact node 0]=])
nbm_bad_case(gap-nan [=[NBM: gaps: non-finite gap at contact node 0]=])
nbm_bad_case(fixed-out-of-range [=[NBM: fixed: index 11 outside \[0, 11\)]=])
nbm_bad_case(fixed-negative [=[NBM: fixed: index -1 outside \[0, 11\)]=])

# ---- construction: options ----
nbm_bad_case(dt-zero [=[NBM: dt: 0(\.0*)?, expected a positive finite time step]=])
nbm_bad_case(dt-negative [=[NBM: dt: -0\.020*, expected a positive finite time step]=])
nbm_bad_case(dt-nan [=[NBM: dt: -?nan, expected a positive finite time step]=])
nbm_bad_case(dt-missing [=[NBM: the time step dt=\.\.\. is required]=])
nbm_bad_case(scheme-unknown [=[NBM: scheme: "implicit", expected "newmark", "explicit" or "moreau-jean"]=])
nbm_bad_case(beta-zero [=[NBM: beta: 0(\.0*)?, expected 0 < beta <= 1/2]=])
nbm_bad_case(beta-large [=[NBM: beta: 0\.60*, expected 0 < beta <= 1/2]=])
nbm_bad_case(gamma-small [=[NBM: gamma: 0\.40*, expected 1/2 <= gamma <= 1]=])
nbm_bad_case(gamma-large [=[NBM: gamma: 1\.50*, expected 1/2 <= gamma <= 1]=])
nbm_bad_case(explicit-dt-critical [=[NBM: dt: 0\.5 exceeds the critical time step [0-9.e+-]+ of the explicit scheme]=])
nbm_bad_case(explicit-with-beta [=[NBM: beta: .*(explicit|newmark)]=])
nbm_bad_case(restitution-range [=[NBM: restitution: 1\.50*, expected a coefficient in \[0, 1\]]=])
nbm_bad_case(restitution-negative [=[NBM: restitution: -0\.20*, expected a coefficient in \[0, 1\]]=])
nbm_bad_case(restitution-newmark [=[NBM: restitution: given with scheme "newmark"]=])
nbm_bad_case(rayleigh-negative [=[NBM: damping a_M: -0\.50*, expected a finite Rayleigh coefficient >= 0]=])
nbm_bad_case(rayleigh-nan [=[NBM: damping b_K: .*nan.*expected a finite Rayleigh coefficient >= 0]=])
nbm_bad_case(damping-size [=[NBM: damping matrix: size 21x21, expected 11x11]=])
nbm_bad_case(damping-nonsymmetric [=[NBM: damping matrix: not symmetric at \([0-9]+, [0-9]+\)]=])
nbm_bad_case(damping-negative [=[NBM: damping matrix: negative diagonal entry]=])
nbm_bad_case(damping-explicit [=[NBM: damping: the explicit scheme takes only mass-proportional damping]=])
nbm_bad_case(moreau-jean-with-gamma [=[NBM: gamma: given with scheme "moreau-jean"]=])
nbm_bad_case(moreau-jean-redistributed [=[NBM: mass: "redistributed" needs scheme "newmark"]=])
nbm_bad_case(mass-unknown [=[NBM: mass: "lumped", expected "consistent" or "redistributed"]=])
nbm_bad_case(positions-missing [=[NBM: positions: size 0, expected 1, 2 or 3 coordinates per dof]=])
nbm_bad_case(positions-size [=[NBM: positions: size 10, expected 1, 2 or 3 coordinates per dof \(n_dofs = 11\)]=])
nbm_bad_case(positions-nan [=[NBM: positions: non-finite coordinates]=])
nbm_bad_case(positions-consistent [=[NBM: positions: given with mass = "consistent"]=])
nbm_bad_case(redistributed-explicit [=[NBM: mass: "redistributed" needs scheme "newmark"]=])

# ---- nbmInit ----
nbm_bad_case(init-u-size [=[nbmInit: u: size 10, expected 11]=])
nbm_bad_case(init-v-size [=[nbmInit: v: size 10, expected 11]=])
nbm_bad_case(init-F-size [=[nbmInit: F: size 21, expected 11]=])
nbm_bad_case(init-F-inf [=[nbmInit: F: non-finite entries]=])
nbm_bad_case(init-u-nan [=[nbmInit: u: non-finite entries]=])
nbm_bad_case(initial-penetration [=[nbmInit: u: initial penetration at contact node 0 \(gap -0\.10*]=])
nbm_bad_case(init-same-array [=[nbmInit: .*u.*v.*same array]=])

# ---- nbmStep ----
nbm_bad_case(step-before-init [=[nbmStep: .*nbmInit]=])
nbm_bad_case(step-F-size [=[nbmStep: F: size 10, expected 11]=])
nbm_bad_case(step-F-inf [=[nbmStep: F: non-finite entries]=])
nbm_bad_case(step-u-resized [=[nbmStep: u: size 12, expected 11]=])
nbm_bad_case(step-v-size [=[nbmStep: v: size 10, expected 11]=])
nbm_bad_case(step-u-modified [=[nbmStep: u, v: changed since the last step]=])
nbm_bad_case(step-same-array [=[nbmStep: .*u.*v.*same array]=])

# ---- nbmRestart ----
nbm_bad_case(restart-unconstructed [=[nbmRestart: the NBM object was not constructed]=])
nbm_bad_case(restart-u-size [=[nbmRestart: u: size 10, expected 11]=])
nbm_bad_case(restart-F-size [=[nbmRestart: F: size 10, expected 11]=])
nbm_bad_case(restart-a-size [=[nbmRestart: a: size 0, expected 11]=])
nbm_bad_case(restart-a-nan [=[nbmRestart: a: non-finite entries]=])
nbm_bad_case(restart-v-inf [=[nbmRestart: v: non-finite entries]=])
nbm_bad_case(restart-t-nan [=[nbmRestart: t: non-finite time]=])
nbm_bad_case(restart-t-negative [=[nbmRestart: t: -0\.10*, expected the saved time >= 0]=])
nbm_bad_case(restart-active-size [=[nbmRestart: active: size 2, expected 1 \(one entry per contact node\)]=])
nbm_bad_case(restart-active-value [=[nbmRestart: active: entry 0 is 2, expected 0 or 1]=])
nbm_bad_case(restart-penetration [=[nbmRestart: u: restored penetration at contact node 0 \(gap -0\.10*]=])
nbm_bad_case(restart-same-array [=[nbmRestart: .*u.*v.*same array]=])
nbm_bad_case(restart-then-modified [=[nbmStep: u, v: changed since the last step]=])

# ---- getters before nbmInit ----
nbm_bad_case(reactions-before-init [=[nbmReactions: call nbmInit first]=])
nbm_bad_case(gaps-before-init [=[nbmGaps: call nbmInit first]=])
nbm_bad_case(active-before-init [=[nbmActive: call nbmInit first]=])
nbm_bad_case(energies-before-init [=[nbmEnergies: call nbmInit first]=])
nbm_bad_case(acceleration-before-init [=[nbmAcceleration: call nbmInit first]=])

# ---- re-linearisation (nbmReplaceContacts) ----
nbm_bad_case(replace-before-init [=[nbmReplaceContacts: no state yet. call nbmInit first]=])
nbm_bad_case(replace-normals-size [=[nbmReplaceContacts: normals: size 0, expected 1 \(one component per contact dof\)]=])
nbm_bad_case(replace-penetrating [=[nbmReplaceContacts: u: initial penetration at contact node 0]=])
nbm_bad_case(replace-penetrating-moreau-jean [=[nbmReplaceContacts: u: penetration at contact node 0 of the new contact description \(gap -0\.010*]=])
nbm_bad_case(replace-u-changed [=[nbmReplaceContacts: u, v: changed since the last step]=])

# ---- an NBM declared without construction ----
nbm_bad_case(unconstructed-step [=[nbmStep: the NBM object was not constructed]=])
nbm_bad_case(unconstructed-init [=[nbmInit: the NBM object was not constructed]=])
nbm_bad_case(unconstructed-time [=[nbmTime: the NBM object was not constructed]=])

# ---- 2D, [P1, P1] (or [P2, P2]) with nbmContactPlane ----
nbm_bad_plane_case(dirichlet-corner [=[NBM: contact dofs: dof [0-9]+ of contact node [0-9]+ is also a fixed \(Dirichlet\) dof]=])
nbm_bad_plane_case(swapped-normals-gaps [=[NBM: normals: size 5, expected 10 ]=])
nbm_bad_plane_case(normals-unnormalised [=[NBM: normals: contact node 0 has \|n\| = 0\.250*, expected a unit vector]=])
nbm_bad_plane_case(initial-penetration [=[nbmInit: u: initial penetration at contact node [0-9]+ \(gap -0\.10*]=])
nbm_bad_plane_case(dofs-other-node [=[NBM: contact dofs: dofs [0-9]+ and [0-9]+ of contact node 0 are at different positions \([0-9.]+ apart, by positions\). expected the 3 components of one node, at one point]=])
nbm_bad_plane_case(F-scalar-space [=[nbmInit: F: size 25, expected 50]=])
nbm_bad_plane_case(explicit-zero-lumped-mass [=[NBM: M \(row-sum lumped\): entry [0-9]+ is -?0(\.0*)?, expected a positive lumped mass]=] -order 2)
