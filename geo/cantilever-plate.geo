// The clamped ("cantilever") plate of the reference paper's Figure 3: a
// rectangle [0, L] x [0, H] clamped on its left edge, whose bottom edge
// beyond x = xc faces a rigid obstacle (the plane y = -gap, set by the
// script). Override with gmsh -setnumber, e.g.
//   gmsh -2 geo/cantilever-plate.geo -setnumber lc 0.1 -format msh22 -o c.msh
// Physical curves (FreeFEM labels): 1 left (clamped), 2 bottom beyond xc
// (contact), 3 bottom before xc, top and right (free).
// Physical surface 1: the plate. Defaults give about 25 linear triangles.
DefineConstant[ L = 1, H = 0.2, xc = 0.5, lc = 0.2 ];

Point(1) = {0, 0, 0, lc};
Point(2) = {xc, 0, 0, lc};
Point(3) = {L, 0, 0, lc};
Point(4) = {L, H, 0, lc};
Point(5) = {0, H, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve(1) = {5};
Physical Curve(2) = {2};
Physical Curve(3) = {1, 3, 4};
Physical Surface(1) = {1};
