// A disc falling on the ground: a curved contact boundary whose nodal normals
// take every direction of the lower half plane. Same parameters and labels as
// bouncing-plate.geo, so that the plate scripts run it with -geo geo/disc.geo:
// W is the diameter (H is not used), the lowest point (W/2, h0) is a node (the
// probe), h0 the gap under it. Labels: 1 the lower half circle (contact),
// 3 the upper half. Override with gmsh -setnumber (W, lc, h0).
DefineConstant[ W = 1, H = 0.5, lc = 0.06, h0 = 0.1 ];

R = W / 2;
Point(1) = {R, h0 + R, 0, lc};      // centre
Point(2) = {R, h0, 0, lc};          // lowest point
Point(3) = {2 * R, h0 + R, 0, lc};
Point(4) = {R, h0 + 2 * R, 0, lc};
Point(5) = {0, h0 + R, 0, lc};
Circle(1) = {5, 1, 2};
Circle(2) = {2, 1, 3};
Circle(3) = {3, 1, 4};
Circle(4) = {4, 1, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve(1) = {1, 2};
Physical Curve(3) = {3, 4};
Physical Surface(1) = {1};
