// A copy of what the command's reports need from a mesh handle: arrays,
// quality and per-tet measures, read once through the public C API.  `bodt
// improve --report` takes one of its input before the run changes it.
#pragma once

#include "bodt.h"

#include <cstdint>
#include <string>
#include <vector>

namespace bodt_cli {

struct MeshSnapshot {
    int32_t nverts = 0, ntets = 0, nfaces = 0;
    int base = 0;  // the handle's index base: the file's (Medit 1, VTK 0) for meshes the command reads
    bodt_quality quality{};
    std::vector<double> xyz;                       // 3 per vertex
    std::vector<int32_t> tets;                     // 4 per tet, in `base`
    std::vector<int32_t> faces, markers;           // 3 (in `base`) and 1 per boundary face
    std::vector<double> min_dihedral, max_dihedral, stretch, volume;  // per tet
};

// False (with `error`: the call that failed and the library's message).
bool take_snapshot(const bodt_mesh* mesh, MeshSnapshot& s, std::string& error);

}  // namespace bodt_cli
