// cases.hpp -- the inputs of bodt_bench: TetGen meshes of surfaces, tet mesh
// files, a random sphere, lazy triangulations of random points in a cube and
// jittered boxes.
#ifndef BODT_BENCH_CASES_HPP
#define BODT_BENCH_CASES_HPP

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace bench {

// A mesh given as arrays, passed to bodt_mesh_create (and, when faces is not
// empty, bodt_mesh_set_boundary_faces with the markers).
struct MeshArrays {
    std::vector<double> xyz;
    std::vector<int32_t> tets;
    int index_base = 0;
    std::vector<int32_t> faces;    // 3 per face, same base
    std::vector<int32_t> markers;  // 1 per face
};

// A prepared case: either a file for bodt_mesh_read or arrays.
struct PreparedMesh {
    bool from_file = false;
    std::string path;   // for from_file (maybe a decompressed copy in a temp dir)
    MeshArrays arrays;  // otherwise
    std::string note;   // e.g. what TetGen made
};

struct Case {
    std::string name;    // unique, file-name safe
    std::string kind;    // "tetgen-surface", "file", "random-sphere", "random-lazy",
                         // "box", "box-stretched", "box-shuffled"
    std::string source;  // the input file or a description
    // Makes the mesh; returns false with a message on failure.
    std::function<bool(PreparedMesh&, std::string&)> prepare;
};

struct CaseOptions {
    std::string shared_dir;      // "" = no shared meshes
    bool large = false;          // add the ~1e5-tet box, the ~1.5e5-tet lazy cube and the 6420-point sphere
    // The scale series instead of the bench set: jittered and stretched
    // Kuhn boxes of n = 12, 26, 55, 119 (6 n^3 tets) up to scale_max tets,
    // and the jittered ones up to 1e6 tets numbered at random (.shuffled).
    bool scale = false;
    double scale_max = 1e6;
    bool with_tetgen = false;    // filled in by the program (compiled with TetGen?)
    std::string temp_dir;        // where .gz files are decompressed
    std::vector<std::string> extra_surfaces;  // --surface FILE
    std::vector<std::string> extra_meshes;    // --mesh FILE
};

// The sides n of the scale series' boxes (6 n^3 tets: about 1e4, 1e5, 1e6,
// 1e7) whose tet count is at most max_tets (with 2% slack: n = 119 makes
// 10 110 954 tets for 1e7).
std::vector<int> scale_box_sizes(double max_tets);

// The bench set.  notes receives one line per input that was skipped (VTK
// files, missing directories, no TetGen).
std::vector<Case> make_cases(const CaseOptions& opt, std::vector<std::string>& notes);

// Decompress a .gz file to dest (zlib, or `gzip -dc` without zlib).
bool gunzip_file(const std::string& src, const std::string& dest, std::string& err);

// The path bodt_mesh_read takes for a tet mesh file: a .gz file (with the
// .node/.ele/.face siblings of a gzipped TetGen file) decompressed into
// temp_dir, since bodt_mesh_read reads plain files only.
bool readable_mesh_path(const std::string& path, const std::string& temp_dir, std::string& out, std::string& err);

// "file.STEM" for a tet mesh file: its name without .gz and the extension,
// file-name safe.
std::string mesh_case_name(const std::string& path);

}  // namespace bench

#endif
