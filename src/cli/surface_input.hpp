// Surface input for the command-line tool: a closed surface (.off, .obj,
// .stl, .ply, read by OpenMesh) or a TetGen PLC (.poly) is tetrahedralized by
// TetGen like `tetgen -p` (constrained Delaunay, no quality refinement).
#pragma once

#include "bodt.h"

#include <string>

namespace bodt_cli {

bool is_surface_path(const std::string& path);

// Returns a bodt status; on failure `message` says why.
int tetrahedralize_surface(const std::string& path, bodt_mesh** mesh, std::string& message);

}  // namespace bodt_cli
