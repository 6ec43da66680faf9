"""quickstart.py: improve a small tet mesh with the Python package bodt (B-ODT)."""
import numpy as np

import bodt

# An octahedron cut into 8 tets around vertex 6, which sits off-centre.
points = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1], [0.45, 0.3, 0.2]])
tets = np.array([[6, 0, 2, 4], [6, 2, 1, 4], [6, 3, 0, 4], [6, 1, 3, 4],
                 [6, 2, 0, 5], [6, 1, 2, 5], [6, 0, 3, 5], [6, 3, 1, 5]])
with bodt.Mesh(points, tets) as mesh:
    before = mesh.quality().min_dihedral
    mesh.improve(max_steps=20)  # B-ODT, the default mode
    print(f"min dihedral: {before:.2f} -> {mesh.quality().min_dihedral:.2f} degrees")
