// `bodt report`: a self-contained HTML page (inline CSS and SVG, no script,
// no external resource) comparing a mesh before and after improvement: the
// quality table, where the worst tets are (report_views.hpp), the boundary
// figures of `bodt compare`, dihedral-angle and stretch histograms, the
// worst tets, and how the mesh was made (report_sections.hpp).  Everything
// comes from mesh snapshots taken through the public C API (bodt.h).
#pragma once

#include "bodt.h"
#include "cli/mesh_snapshot.hpp"
#include "cli/run_record.hpp"

#include <string>

namespace bodt_cli {

// Writes a self-contained HTML report comparing two meshes (the original and
// the improved one); `run` (may be nullptr) says how the improved one was
// made.  The names (file paths, usually) are shown escaped.  Returns false
// and sets `error` if the file cannot be written.
bool write_report(const MeshSnapshot& original, const MeshSnapshot& improved, const std::string& original_name,
                  const std::string& improved_name, const RunRecord* run, const std::string& out_path,
                  std::string& error);

// The report's HTML as a string (what write_report writes).
bool render_report(const MeshSnapshot& original, const MeshSnapshot& improved, const std::string& original_name,
                   const std::string& improved_name, const RunRecord* run, std::string& html, std::string& error);

}  // namespace bodt_cli
