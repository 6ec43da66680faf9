// `bodt report`: a self-contained HTML page (inline CSS and SVG, no script,
// no external resource) comparing a mesh before and after improvement: the
// quality table, dihedral-angle and stretch histograms, and the worst tets.
// Everything goes through the public C API (bodt.h).
#pragma once

#include "bodt.h"

#include <string>

namespace bodt_cli {

// Writes a self-contained HTML report comparing two meshes (the original and
// the improved one).  The names (file paths, usually) are shown escaped.
// Returns false and sets `error` if the file cannot be written or a C API
// call fails.
bool write_report(const bodt_mesh* original, const bodt_mesh* improved,
                  const std::string& original_name, const std::string& improved_name,
                  const std::string& out_path, std::string& error);

// The report's HTML as a string (what write_report writes).
bool render_report(const bodt_mesh* original, const bodt_mesh* improved,
                   const std::string& original_name, const std::string& improved_name,
                   std::string& html, std::string& error);

}  // namespace bodt_cli
