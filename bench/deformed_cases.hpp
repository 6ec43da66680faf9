// deformed_cases.hpp -- the inputs of bodt_bench_deformed: an undeformed
// mesh (the reference) and a deformed copy of it with the same vertex
// numbering and tets, possibly with inverted tets (paper 002, sec. 4).
#ifndef BODT_BENCH_DEFORMED_CASES_HPP
#define BODT_BENCH_DEFORMED_CASES_HPP

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace bench {

struct DeformedMesh {
    std::vector<double> original;  // 3 per vertex: the reference
    std::vector<double> deformed;  // 3 per vertex: the same vertices, moved
    std::vector<int32_t> tets;     // 4 per tet, 0-based, shared by both
    std::vector<int32_t> regions;  // one per tet, or empty
    std::vector<int32_t> faces;    // marked faces (3 per face, 0-based) ...
    std::vector<int32_t> markers;  // ... and their markers (non-zero)
    int32_t inverted = 0;          // tets the deformation turned over
    std::string note;              // what was made
};

struct DeformedCase {
    std::string name;    // unique, file-name safe
    std::string kind;    // "hole-box" or "file"
    std::string source;  // what the mesh is
    std::string deformation;
    std::function<bool(DeformedMesh&, std::string&)> prepare;
};

// The box with a hole deformed by DP, RC and DP+RC+PH; then the default
// shared meshes (those found under shared_dir/meshes/tet) and extra_meshes,
// their boundary vertices beyond the bounding box's middle plane x = xmid
// moved to xmid + file_stretch (x - xmid) (interior vertices stay).  .gz
// files are decompressed into temp_dir.  notes receives a line per mesh not
// found.
std::vector<DeformedCase> make_deformed_cases(const std::string& shared_dir, const std::vector<std::string>& extra_meshes,
                                              double file_stretch, const std::string& temp_dir,
                                              std::vector<std::string>& notes);

}  // namespace bench

#endif
