// The clamped ("cantilever") plate of the reference paper's Figure 3: a
// rectangle [0, L] x [0, H] clamped on its left edge, whose right edge faces
// a rigid wall (the plane x = L + gap, set by the script). Override with
// gmsh -setnumber, e.g.
//   gmsh -2 geo/cantilever-plate.geo -setnumber lc 0.1 -format msh22 -o c.msh
// Physical curves (FreeFEM labels): 1 left (clamped), 2 right (contact),
// 3 bottom and top (free). Physical surface 1: the plate.
// Defaults give 26 linear triangles.
DefineConstant[ L = 1, H = 0.25, lc = 0.19 ];

Point(1) = {0, 0, 0, lc};
Point(2) = {L, 0, 0, lc};
Point(3) = {L, H, 0, lc};
Point(4) = {0, H, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve(1) = {4};
Physical Curve(2) = {2};
Physical Curve(3) = {1, 3};
Physical Surface(1) = {1};
