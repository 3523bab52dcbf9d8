// The bouncing plate (reference paper Figure 2): a rectangle of width W and
// height H whose bottom edge starts at height h0 above the rigid ground y = 0.
// Override with gmsh -setnumber, e.g.
//   gmsh -2 geo/bouncing-plate.geo -setnumber lc 0.03 -format msh22 -o plate.msh
// Physical curves (FreeFEM labels): 1 bottom (contact), 2 right, 3 top, 4 left.
// Physical surface 1: the plate. The bottom edge has a node at its middle
// (the probe of the examples). Defaults give about 400 linear triangles.
DefineConstant[ W = 1, H = 0.5, lc = 0.058, h0 = 0.1 ];

Point(1) = {0, h0, 0, lc};
Point(5) = {W / 2, h0, 0, lc};
Point(2) = {W, h0, 0, lc};
Point(3) = {W, h0 + H, 0, lc};
Point(4) = {0, h0 + H, 0, lc};
Line(1) = {1, 5};
Line(5) = {5, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 5, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve(1) = {1, 5};
Physical Curve(2) = {2};
Physical Curve(3) = {3};
Physical Curve(4) = {4};
Physical Surface(1) = {1};
