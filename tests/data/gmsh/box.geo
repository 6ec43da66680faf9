// Two unit cubes side by side, [0,1]x[0,1]^2 and [1,2]x[0,1]^2, meshed
// coarsely for the Gmsh reader tests (tests/test_io_gmsh.cpp).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Physical Volume("left", 1) = Volume In BoundingBox{-0.1, -0.1, -0.1, 1.1, 1.1, 1.1};
Physical Volume("right", 2) = Volume In BoundingBox{0.9, -0.1, -0.1, 2.1, 1.1, 1.1};
// the bottom z = 0 (two faces)
Physical Surface("bottom", 10) = Surface In BoundingBox{-0.1, -0.1, -0.1, 2.1, 1.1, 0.1};
// the edge x = 0, y = 0
Physical Curve("edge", 20) = Curve In BoundingBox{-0.1, -0.1, -0.1, 0.1, 0.1, 1.1};
// the corner at the origin
Physical Point("corner", 30) = Point In BoundingBox{-0.1, -0.1, -0.1, 0.1, 0.1, 0.1};
Mesh.MeshSizeMin = 1;
Mesh.MeshSizeMax = 1;
