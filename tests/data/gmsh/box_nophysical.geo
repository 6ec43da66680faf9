// box.geo without physical groups, for the Gmsh reader tests
// (tests/test_io_gmsh.cpp): Gmsh then saves every element, and the tets of
// each volume carry only the volume's entity tag.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.MeshSizeMin = 1;
Mesh.MeshSizeMax = 1;
