// Medit binary .meshb (libMeshb's "GMF" binary layout): the same sections as
// the ASCII .mesh of medit.cpp, with the same mapping to MeshData.  Every
// malformed, truncated or oversized file is an Error(BODT_ERR_IO) naming the
// path and the byte offset.
#pragma once

#include <string>

#include "io/mesh_io.hpp"

namespace bodt {

// Reads versions 1 to 4, little- and big-endian.  The result counts vertices
// from 1 (base = 1), as the file does.
MeshData read_medit_binary(const std::string& path);

// Writes version 2 (64-bit reals, 32-bit integers and positions),
// little-endian, or version 3 (64-bit positions) when the file would reach
// 2 GiB.
void write_medit_binary(const std::string& path, const MeshData& data);

}  // namespace bodt
