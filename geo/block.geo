// A rectangular block for the 3D examples and tests: [0, Lx] x [0, Ly] x
// [h0, h0 + Lz] (gmsh OpenCASCADE box). Override with gmsh -setnumber
// (Lx, Ly, Lz, h0, lc), e.g.
//   gmsh -3 geo/block.geo -setnumber lc 0.1 -format msh22 -o block.msh
// Physical surfaces (FreeFEM labels with gmshload3): 1 the bottom face
// z = h0 (contact), 2 the other five faces. Physical volume 1: the block.
SetFactory("OpenCASCADE");
DefineConstant[ Lx = 0.6, Ly = 0.4, Lz = 0.3, h0 = 0.1, lc = 0.1 ];
Box(1) = {0, 0, h0, Lx, Ly, Lz};
MeshSize{ PointsOf{ Volume{1}; } } = lc;
Physical Surface(1) = {5};
Physical Surface(2) = {1, 2, 3, 4, 6};
Physical Volume(1) = {1};
