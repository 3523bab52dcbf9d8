# Rigid obstacles (method.md §8; included from tests/scripts/CMakeLists.txt):
# the helpers of edp/nbm.idp against closed forms, and NBM runs whose checks
# come from mechanics, not from earlier runs of the code.

# Normals, gaps, dof pairing, reach, true distances and moving-obstacle arrays
# against closed forms (2D and 3D).
nbm_script_test(obstacle-helpers ${CMAKE_CURRENT_SOURCE_DIR}/obstacle-helpers.edp)

# geo/disc.geo on frictionless planes at 30 and 15 degrees (and flat ground):
# at every step the tangential acceleration of the centre of mass is g sin(a)
# to 1e-10 relative (the contact forces are normal to the plane) and the
# geometric penetration of the deformed contact nodes is <= 1e-12 of the
# displacement scale (the script exits 1 otherwise). P1, P2, both masses.
foreach(angle 30 15 0)
  foreach(order 1 2)
    foreach(mass consistent redistributed)
      nbm_script_test(obstacle-disc-slope-${angle}-P${order}-${mass} ${EDP}/disc-slope.edp
        -angle ${angle} -order ${order} -mass ${mass} -T 0.5 -vtkFrames 0 -plot 0
        -out obstacle-disc-slope-${angle}-P${order}-${mass})
    endforeach()
  endforeach()
endforeach()

# Rigid circles (nbmContactCircle): the plate on a cylinder, centred and
# off-centre, and the disc inside a circular casing. At every step, with u_t
# the displacement of node k orthogonal to its normal: outside (convex), the
# true distance is >= 0 and a closed contact sits at sqrt(R^2 + |u_t|^2) - R
# (<= |u_t|^2/(2R)); inside, the distance is >= R - sqrt(R^2 + |u_t|^2)
# (>= -|u_t|^2/(2R)); 1e-12 of the displacement scale for round-off. The body
# must touch the obstacle. With -follow 1 (massless boundary) the circle is
# held exactly (NBMObstacle, method.md §10): no node inside it, every
# closed contact on it and nbmGaps the true distances, to 1e-12 of the
# displacement scale, after a slide of 0.3.
foreach(variant
    "plate-cylinder-P1;-offset;0"
    "plate-cylinder-off-P2;-offset;0.2;-order;2;-T;0.6"
    "plate-cylinder-redistributed;-offset;0.1;-mass;redistributed;-T;0.6"
    "plate-cylinder-follow;-offset;0.3;-mass;redistributed;-follow;1"
    "plate-cylinder-follow-P2;-offset;0.3;-order;2;-mass;redistributed;-follow;1;-T;0.6"
    "disc-casing-P1;-geo;disc.geo;-side;inside;-Rc;0.8"
    "disc-casing-P2-redistributed;-geo;disc.geo;-side;inside;-Rc;0.8;-order;2;-mass;redistributed")
  list(POP_FRONT variant name)
  nbm_script_test(obstacle-${name} ${EDP}/plate-cylinder.edp ${variant} -vtkFrames 0 -plot 0 -out obstacle-${name})
endforeach()

# 3D: the gmsh block (geo/block.geo) on planes inclined at 20 and 35 degrees
# about y, and on flat ground: the same two checks as the disc (tangential
# acceleration g sin(a) to 1e-10 relative, geometric penetration <= 1e-12 of
# the displacement scale, every step); the block must touch the plane. On a
# rigid cylinder (axis along y) and a sphere, body outside: no geometric
# penetration and every closed contact at sqrt(R^2 + |u_t|^2) - R, u_t
# orthogonal to the node's normal (and to the cylinder's axis). With
# -contactFree 1 (the plane out of reach, scripts/drop-3d-scale.sh) the block
# must never touch it and falls freely (the same acceleration check).
foreach(variant
    "20-P1;-angle;20"
    "20-P1-contact-free;-angle;20;-contactFree;1"
    "20-P1-redistributed;-angle;20;-mass;redistributed"
    "35-P2;-angle;35;-order;2"
    "35-P2-redistributed;-angle;35;-order;2;-mass;redistributed"
    "flat-P1;-angle;0"
    "cylinder-P1;-obstacle;cylinder;-offset;0.2"
    "cylinder-P2-redistributed;-obstacle;cylinder;-order;2;-mass;redistributed"
    "sphere-P1;-obstacle;sphere;-offset;0.1"
    "sphere-P2;-obstacle;sphere;-order;2;-offset;0")
  list(POP_FRONT variant name)
  nbm_script_test(obstacle-drop-3d-${name} ${EDP}/drop-3d.edp ${variant} -vtkFrames 0 -plot 0 -out obstacle-drop-3d-${name})
endforeach()

# Obstacles held exactly, the contact frame following the body (NBMObstacle,
# obstacle=; method.md §10). edp/disc-bowl.edp checks at every step that every
# contact node is outside the circle (true distance from the deformed
# positions, computed by the script) and every closed contact on it, to 1e-12
# of the diameter, and that nbmGaps gives those distances; against the rigid
# frictionless disc (RK4 in the script): the angle of the centre of mass in a
# bowl (P1 and P2, two materials and step sizes) and the angle where the disc
# leaves a cylinder, acos(2/3 cos theta0), with the energy balance. The
# thresholds sit above the measured values (bowl P1: 9e-4 rad, 8e-6 m g r;
# P2: 7e-3 rad, 1.4e-4 m g r; cylinder: 0.822 against 0.859 rad): a regression
# of the frame iteration or of the mass moves them by orders of magnitude.
foreach(variant
    "bowl-P1;-side;inside;-maxAngleError;0.003;-maxEnergyDrift;1e-4"
    "bowl-P2-nu045-dt2e-3;-side;inside;-order;2;-nu;0.45;-dt;2e-3;-lc;0.06;-maxAngleError;0.015;-maxEnergyDrift;1e-3"
    "cylinder-P1;-side;outside;-Rb;1;-theta0;11.4591559;-E;1e5;-rayleighK;2e-3;-maxDetachError;0.06;-maxEnergyDrift;5e-3")
  list(POP_FRONT variant name)
  nbm_script_test(obstacle-follow-disc-${name} ${EDP}/disc-bowl.edp ${variant} -vtkFrames 0 -plot 0
    -out obstacle-follow-disc-${name})
endforeach()
# Turning obstacles and the script's own signed distance (NBMObstacle
# rotation = / pivot =, kind "distance"): edp/disc-bowl.edp checks every step
# as above (true distances from the script's closed form of the turning
# circle, 1e-12 of the diameter) and the energy balance with the obstacle's
# work (measured 6.5e-4 m g r over 1 s for a bowl turning at 2 rad/s about a
# point 0.1 off its centre; the bound sits above it). The script's distance of
# the bowl gives the rigid-pendulum checks of the circle, and the same run as
# the circle to 1e-6 of each column (measured 7e-10 and 1.6e-9: the central
# differences of its gradient), fixed and turning (tests/scripts/obstacle-forms.sh); so
# do a sphere, a cylinder (P2) and an inclined plane in 3D (drop-3d.edp,
# measured 2e-9 to 8e-9). A disc sliding off a turning cylinder (measured
# balance 1.9e-4 m g r) is checked alone: it bounces as it leaves, and its
# impacts amplify the differences of the two forms to 1e-6 of its state
# (measured), which is the run's sensitivity, not an error of either form.
nbm_script_test(obstacle-follow-disc-bowl-distance ${EDP}/disc-bowl.edp -side inside -shape distance
  -maxAngleError 0.003 -maxEnergyDrift 1e-4 -vtkFrames 0 -plot 0 -out obstacle-follow-disc-bowl-distance)
nbm_script_test(obstacle-follow-disc-turning-bowl ${EDP}/disc-bowl.edp -side inside -spin 2 -eccentricity 0.1
  -T 1 -maxEnergyDrift 2e-3 -vtkFrames 0 -plot 0 -out obstacle-follow-disc-turning-bowl)
nbm_script_test(obstacle-follow-disc-turning-cylinder ${EDP}/disc-bowl.edp -side outside -Rb 1 -theta0 11.4591559
  -E 1e5 -rayleighK 2e-3 -spin -1 -eccentricity 0.05 -T 1 -maxEnergyDrift 1e-3 -vtkFrames 0 -plot 0
  -out obstacle-follow-disc-turning-cylinder)
set(NBM_OBSTACLE_FORMS ${CMAKE_CURRENT_SOURCE_DIR}/obstacle-forms.sh)
foreach(case
    "disc-bowl;${EDP}/disc-bowl.edp;-shape circle;-shape distance;-side;inside;-T;0.5"
    "disc-turning-bowl;${EDP}/disc-bowl.edp;-shape circle;-shape distance;-side;inside;-spin;2;-eccentricity;0.1;-T;1"
    "drop-3d-sphere;${EDP}/drop-3d.edp;-shape kind;-shape distance;-mass;redistributed;-follow;1;-obstacle;sphere;-offset;0.1"
    "drop-3d-cylinder-P2;${EDP}/drop-3d.edp;-shape kind;-shape distance;-mass;redistributed;-follow;1;-obstacle;cylinder;-offset;0.2;-order;2"
    "drop-3d-incline;${EDP}/drop-3d.edp;-shape kind;-shape distance;-mass;redistributed;-follow;1;-angle;20")
  list(POP_FRONT case name script a b)
  add_test(NAME script.obstacle-forms-${name}
    COMMAND bash ${NBM_OBSTACLE_FORMS} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${script}
            obstacle-forms-${name} 1e-6 ${a} ${b} ${case} -vtkFrames 0 -plot 0
    WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
  set_tests_properties(script.obstacle-forms-${name} PROPERTIES TIMEOUT 900 LABELS script)
endforeach()
# The 3D block of drop-3d.edp held exactly (-follow 1, massless boundary) on
# a sphere and a cylinder, off-centre, and on the 20-degree incline: closed
# contacts on the true surface and nbmGaps the true distances, every step.
foreach(variant
    "sphere-P1;-obstacle;sphere;-offset;0.1"
    "sphere-P2;-obstacle;sphere;-order;2;-offset;0.15;-T;1.0"
    "cylinder-P2;-obstacle;cylinder;-order;2;-offset;0.2"
    "incline-20-P1;-angle;20")
  list(POP_FRONT variant name)
  nbm_script_test(obstacle-follow-drop-3d-${name} ${EDP}/drop-3d.edp ${variant} -mass redistributed
    -follow 1 -vtkFrames 0 -plot 0 -out obstacle-follow-drop-3d-${name})
endforeach()

# Bad input of the obstacle helpers (tests/scripts/bad-input/obstacles.edp):
# each misuse stops with a message naming the argument (no ';' in the
# regexes: they would split the list) (the helpers print it,
# then assert: an ExecError); `valid` runs every helper correctly.
set(NBM_BAD_OBST ${CMAKE_CURRENT_SOURCE_DIR}/bad-input/obstacles.edp)
add_test(NAME bad-input.obstacles-valid
  COMMAND bash ${NBM_RUN_FREEFEM} ${CMAKE_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${NBM_BAD_OBST} -case valid
  WORKING_DIRECTORY ${NBM_SCRIPT_OUT})
set_tests_properties(bad-input.obstacles-valid PROPERTIES TIMEOUT 300 LABELS bad-input)
foreach(case
    [=[plane-normal-zero;nbmContactPlane: the plane normal \(0, 0\) is zero or not finite]=]
    [=[plane-normal-nan;nbmContactPlane: the plane normal \(-?nan, 1\) is zero or not finite]=]
    [=[plane3-normal-zero;nbmContactPlane3: the plane normal nu \(0, 0, 0\) is zero or not finite, expected a non-zero vector]=]
    [=[label-empty;nbmContactPlane: label 7 has no node in this space]=]
    [=[label-empty-3d;nbmContactPlane3: label 9 has no node in this space]=]
    [=[reach-negative;nbmContactPlane: nbmReach = -1, expected a distance >= 0]=]
    [=[reach-leaves-none;nbmContactCircle: no node of label 1 within nbmReach = 0\.01 of the obstacle]=]
    [=[circle-radius-zero;nbmContactCircle: R = 0, expected a positive finite radius]=]
    [=[circle-radius-negative;nbmContactCircle: R = -2, expected a positive finite radius]=]
    [=[circle-side;nbmContactCircle: side = "below", expected "outside" \(the body is outside the obstacle\) or "inside"]=]
    [=[circle-centre-on-a-node;nbmContactCircle: the obstacle's distance at the node \(0\.5, 0\.1\) is .* expected a finite value and a finite non-zero gradient]=]
    [=[sphere-radius-nan;nbmContactSphere: R = -?nan, expected a positive finite radius]=]
    [=[sphere-side;nbmContactSphere: side = "Outside", expected "outside"]=]
    [=[cylinder-axis-zero;nbmContactCylinder: the axis a \(0, 0, 0\) is zero or not finite]=]
    [=[cylinder-axis-through-a-node;nbmContactCylinder: the obstacle's distance at the node \([0-9.]+, 0\.5, 0\.1\) is 2 with gradient \(-?0, -?0, -?0\)]=]
    [=[cylinder-radius;nbmContactCylinder: R = -1, expected a positive finite radius]=]
    [=[phi-constant;nbmContactPhi: the obstacle's distance at the node \([0-9.e-]+, [0-9.e-]+\) is 1 with gradient \(0, 0\). expected a finite value and a finite non-zero gradient]=]
    [=[phi-nan;nbmContactPhi: the obstacle's distance at the node .* is -?nan]=]
    [=[phi3-constant;nbmContactPhi3: the obstacle's distance at the node .* with gradient \(0, 0, 0\)]=]
    [=[distance-side;nbmDistanceCircle: side = "out", expected "outside"]=]
    [=[distance-radius;nbmDistanceSphere: R = 0, expected a positive finite radius]=]
    [=[distance-plane-normal;nbmDistancePlane: the plane normal nu \(0, 0, 0\) is zero]=]
    [=[moving-plane-nan;nbmMovingPlane: w, w', w'' = 0, -?nan, 0, expected finite values]=])
  list(POP_FRONT case name)
  nbm_bad_input_test(obstacles-${name} "${case}" ${NBM_BAD_OBST} -case ${name})
endforeach()

# The same disc checks with the plane given as a script signed distance
# (nbmContactPhiGrad, nbmDistancePhi) and with the contact nodes narrowed by
# nbmReach (8 of the 29 nodes; the helper reports the 21 it leaves out).
nbm_script_test(obstacle-disc-slope-phi-P2 ${EDP}/disc-slope.edp -phi 1 -order 2 -T 0.5 -vtkFrames 0 -plot 0
  -out obstacle-disc-slope-phi-P2)
nbm_script_test(obstacle-disc-slope-reach-redistributed ${EDP}/disc-slope.edp -reach 0.15 -mass redistributed
  -T 0.5 -vtkFrames 0 -plot 0 -out obstacle-disc-slope-reach-redistributed)
