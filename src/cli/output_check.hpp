// Checks of an output path made before any input is read, so that a bad
// extension or an unwritable place is found in a moment and not after a
// long run.
#pragma once

#include <string>

namespace bodt_cli {

// The enum bodt_format that a mesh file named `path` is written in: `format`
// itself unless it is BODT_FORMAT_AUTO, else the format of the extension
// (the table of bodt_mesh_write, src/io/mesh_io.cpp: .mesh, .meshb, .node,
// .ele, .msh, .vtu, .vtk, .inp, in any case).  False (with `error`) for an
// unknown extension.
bool output_format(const std::string& path, int format, int& resolved, std::string& error);

// Whether a file can be written at `path`: its directory exists and may be
// written to, and the path is not a directory, nor an existing file that may
// not be written.  With `tetgen`, the same for the .node, .ele and .face
// files a TetGen write makes beside it.  Nothing is created.  False with
// `error` saying what is wrong.
bool writable(const std::string& path, bool tetgen, std::string& error);

// Both checks for a mesh file to be written in `format` (or by its extension).
bool check_mesh_output(const std::string& path, int format, std::string& error);

}  // namespace bodt_cli
