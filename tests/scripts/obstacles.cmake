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
# must touch the obstacle.
foreach(variant
    "plate-cylinder-P1;-offset;0"
    "plate-cylinder-off-P2;-offset;0.2;-order;2;-T;0.6"
    "plate-cylinder-redistributed;-offset;0.1;-mass;redistributed;-T;0.6"
    "disc-casing-P1;-geo;disc.geo;-side;inside;-Rc;0.8"
    "disc-casing-P2-redistributed;-geo;disc.geo;-side;inside;-Rc;0.8;-order;2;-mass;redistributed")
  list(POP_FRONT variant name)
  nbm_script_test(obstacle-${name} ${EDP}/plate-cylinder.edp ${variant} -vtkFrames 0 -plot 0 -out obstacle-${name})
endforeach()

# 3D: the gmsh block (geo/block.geo) on planes inclined at 20 and 35 degrees
# about y, and on flat ground: the same two checks as the disc (tangential
# acceleration g sin(a) to 1e-10 relative, geometric penetration <= 1e-12 of
# the displacement scale, every step); the block must touch the plane.
foreach(variant
    "20-P1;-angle;20"
    "20-P1-redistributed;-angle;20;-mass;redistributed"
    "35-P2;-angle;35;-order;2"
    "35-P2-redistributed;-angle;35;-order;2;-mass;redistributed"
    "flat-P1;-angle;0")
  list(POP_FRONT variant name)
  nbm_script_test(obstacle-drop-3d-${name} ${EDP}/drop-3d.edp ${variant} -vtkFrames 0 -plot 0 -out obstacle-drop-3d-${name})
endforeach()
