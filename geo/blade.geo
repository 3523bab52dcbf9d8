// A blade-like plate for the 3D forced-response example (edp/forced-blade-3d.edp):
// the box [0, L] x [0, W] x [0, H] (span L along x, chord W along y,
// thickness H along z; gmsh OpenCASCADE), clamped at its root x = 0, its tip
// x = L facing the casing. The mesh size grows as (x / L)^4 from lcRoot at the
// root to lcTip at the tip (fine over most of the span, coarse at the tip:
// few contact nodes there). Override with gmsh -setnumber, e.g.
//   gmsh -3 geo/blade.geo -setnumber lcRoot 0.03 -setnumber lcTip 0.06 -format msh22 -o blade.msh
// Physical surfaces (FreeFEM labels with gmshload3): 1 the root face x = 0,
// 2 the tip face x = L (contact), 3 the other four faces. Physical volume 1.
SetFactory("OpenCASCADE");
DefineConstant[ L = 1, W = 0.3, H = 0.06, lcRoot = 0.04, lcTip = 0.04 ];
Box(1) = {0, 0, 0, L, W, H};
Field[1] = MathEval;
Field[1].F = Sprintf("%g + (%g - %g) * (x / %g)^4", lcRoot, lcTip, lcRoot, L);
Background Field = 1;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Surface(1) = {1};
Physical Surface(2) = {2};
Physical Surface(3) = {3, 4, 5, 6};
Physical Volume(1) = {1};
