#include "io/vtk_cells.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <cstdint>
#include <limits>
#include <set>
#include <utility>

namespace bodt {

const char* vtk_cell_type_name(int64_t type) {
    switch (type) {
        case 1: return "vertex";
        case 2: return "poly-vertex";
        case 3: return "line";
        case 4: return "poly-line";
        case 5: return "triangle";
        case 6: return "triangle strip";
        case 7: return "polygon";
        case 8: return "pixel";
        case 9: return "quad";
        case 10: return "tetra";
        case 11: return "voxel";
        case 12: return "hexahedron";
        case 13: return "wedge";
        case 14: return "pyramid";
        case 15: return "pentagonal prism";
        case 16: return "hexagonal prism";
        case 21: return "quadratic edge";
        case 22: return "quadratic triangle";
        case 23: return "quadratic quad";
        case 24: return "quadratic tetra";
        case 25: return "quadratic hexahedron";
        case 42: return "polyhedron";
        default: return nullptr;
    }
}

namespace {

// The arrays read for each kind of data, in order of precedence.
const char* const kRegionArrays[] = {"region", "gmsh:physical", "CellEntityIds", "medit:ref"};
const char* const kMarkerArrays[] = {"marker", "gmsh:physical", "CellEntityIds", "medit:ref"};
const char* const kRefArrays[] = {"ref", "medit:ref"};
const char* const kFixedArrays[] = {"fixed"};
const char* const kCornerArrays[] = {"corner"};

template <size_t N>
bool listed(const char* const (&names)[N], const std::string& name) {
    for (const char* n : names)
        if (name == n) return true;
    return false;
}

// The first of `names` that `arrays` has, or an empty array; not a copy
// (one array may serve two lists, gmsh:physical as regions and markers).
template <size_t N>
const std::vector<int64_t>& first_of(const std::map<std::string, std::vector<int64_t>>& arrays,
                                     const char* const (&names)[N]) {
    static const std::vector<int64_t> none;
    for (const char* n : names) {
        const auto it = arrays.find(n);
        if (it != arrays.end()) return it->second;
    }
    return none;
}

}  // namespace

bool vtk_reads_cell_array(const std::string& name) {
    return listed(kRegionArrays, name) || listed(kMarkerArrays, name);
}

bool vtk_reads_point_array(const std::string& name) {
    return listed(kFixedArrays, name) || listed(kCornerArrays, name) || listed(kRefArrays, name);
}

MeshData mesh_from_vtk(VtkGrid g, const VtkFail& fail) {
    const std::vector<int64_t>& region = first_of(g.cell_arrays, kRegionArrays);
    const std::vector<int64_t>& marker = first_of(g.cell_arrays, kMarkerArrays);
    const std::vector<int64_t>& ref = first_of(g.point_arrays, kRefArrays);
    const std::vector<int64_t>& fixed = first_of(g.point_arrays, kFixedArrays);
    const std::vector<int64_t>& corner = first_of(g.point_arrays, kCornerArrays);
    const int64_t ncells = static_cast<int64_t>(g.types.size());
    const int64_t nconn = static_cast<int64_t>(g.connectivity.size());
    if (static_cast<int64_t>(g.offsets.size()) != ncells)
        fail(VtkPart::Offsets, std::to_string(ncells) + " cell types but " + std::to_string(g.offsets.size()) +
                                   " cells");
    for (int64_t c = 0; c < ncells; ++c) {
        const int64_t start = c == 0 ? 0 : g.offsets[c - 1];
        const int64_t end = g.offsets[c];
        if (end <= start)
            fail(VtkPart::Offsets, "the offsets are not increasing: cell " + std::to_string(c) + " ends at " +
                                       std::to_string(end) + ", after " + std::to_string(start));
        if (end > nconn)
            fail(VtkPart::Offsets, "offset " + std::to_string(end) + " of cell " + std::to_string(c) +
                                       " is beyond the " + std::to_string(nconn) + " connectivity entries");
    }
    if (ncells > 0 && g.offsets.back() != nconn)
        fail(VtkPart::Offsets, "the offsets use " + std::to_string(g.offsets.back()) + " of the " +
                                   std::to_string(nconn) + " connectivity entries");
    if (ncells == 0 && nconn != 0) fail(VtkPart::Connectivity, "connectivity entries but no cells");
    for (int64_t k = 0; k < nconn; ++k)
        if (g.connectivity[k] < 0 || g.connectivity[k] >= g.points)
            fail(VtkPart::Connectivity, "connectivity entry " + std::to_string(k) + " is " +
                                            std::to_string(g.connectivity[k]) + ", out of range for " +
                                            std::to_string(g.points) + " points");

    MeshData d;
    d.base = 0;
    d.xyz = std::move(g.xyz);
    for (int64_t c = 0; c < ncells; ++c) {
        const int64_t t = g.types[c];
        const int64_t start = c == 0 ? 0 : g.offsets[c - 1];
        const int64_t n = g.offsets[c] - start;
        int64_t expect = 0;
        switch (t) {
            case kVtkTetra: expect = 4; break;
            case kVtkTriangle: expect = 3; break;
            case kVtkLine: expect = 2; break;
            case kVtkVertex: expect = 1; break;
            default: {
                const char* tn = vtk_cell_type_name(t);
                fail(VtkPart::Types, "cell " + std::to_string(c) + " has VTK type " + std::to_string(t) +
                                         (tn ? std::string(" (") + tn + ")" : std::string()) +
                                         ": only tetrahedra (10), with triangles (5), lines (3) and "
                                         "vertices (1), are supported");
            }
        }
        if (n != expect)
            fail(VtkPart::Offsets, "cell " + std::to_string(c) + " (" + vtk_cell_type_name(t) + ") has " +
                                       std::to_string(n) + " points instead of " + std::to_string(expect));
        const int64_t* v = g.connectivity.data() + start;
        if (t == kVtkTetra) {
            for (int k = 0; k < 4; ++k) d.tets.push_back(static_cast<int32_t>(v[k]));
            if (!region.empty()) d.regions.push_back(static_cast<int32_t>(region[c]));
        } else if (t == kVtkTriangle) {
            for (int k = 0; k < 3; ++k) d.triangles.push_back(static_cast<int32_t>(v[k]));
            d.tri_markers.push_back(marker.empty() ? 0 : static_cast<int32_t>(marker[c]));
        } else if (t == kVtkLine) {
            d.feature_edges.push_back(static_cast<int32_t>(v[0]));
            d.feature_edges.push_back(static_cast<int32_t>(v[1]));
            d.edge_refs.push_back(marker.empty() ? 0 : static_cast<int32_t>(marker[c]));
        }
    }
    if (d.tets.empty()) fail(VtkPart::Grid, "the file has no tetrahedra (VTK_TETRA cells)");
    if (d.tets.size() / 4 > static_cast<size_t>(INT32_MAX)) fail(VtkPart::Grid, "more than 2^31 - 1 tets");
    for (size_t k = 0; k < fixed.size(); ++k)
        if (fixed[k] != 0) d.fixed.push_back(static_cast<int32_t>(k));
    for (size_t k = 0; k < corner.size(); ++k)
        if (corner[k] != 0) d.corners.push_back(static_cast<int32_t>(k));
    d.vertex_refs.assign(ref.begin(), ref.end());  // each checked to fit in 32 bits
    return d;
}

VtkCellWriter::VtkCellWriter(const std::string& path, const MeshData& d)
    : d_(d), nv_(d.xyz.size() / 3), nt_(d.tets.size() / 4), nf_(d.triangles.size() / 3),
      ne_(d.feature_edges.size() / 2) {
    auto invalid = [&](const std::string& message) {
        throw Error(BODT_ERR_INVALID_ARGUMENT, "writing '" + path + "': " + message);
    };
    if (d.xyz.size() % 3 || d.tets.size() % 4 || d.triangles.size() % 3 || d.feature_edges.size() % 2)
        invalid("an array size is not a multiple of its record size");
    if (!d.regions.empty() && d.regions.size() != nt_) invalid("regions must have one value per tet");
    if (d.tri_markers.size() != nf_) invalid("tri_markers must have one value per triangle");
    if (!d.vertex_refs.empty() && d.vertex_refs.size() != nv_) invalid("vertex_refs must have one value per vertex");
    if (!d.edge_refs.empty() && d.edge_refs.size() != ne_) invalid("edge_refs must have one value per feature edge");
    auto check_index = [&](int32_t v) {
        const int64_t i = static_cast<int64_t>(v) - d.base;
        if (i < 0 || i >= static_cast<int64_t>(nv_)) invalid("vertex " + std::to_string(v) + " is out of range");
    };
    for (int32_t v : d.tets) check_index(v);
    for (int32_t v : d.triangles) check_index(v);
    for (int32_t v : d.feature_edges) check_index(v);
    for (int32_t v : d.fixed) check_index(v);
    for (int32_t v : d.corners) check_index(v);
    std::set<std::string> names = {"region", "marker"};
    for (const auto& field : d.tet_fields) {
        if (field.values.size() != nt_) invalid("tet field '" + field.name + "' must have one value per tet");
        if (field.name.empty()) invalid("a tet field has no name");
        if (!names.insert(field.name).second) invalid("tet field name '" + field.name + "' is used twice or reserved");
    }
}

int32_t VtkCellWriter::connectivity(uint64_t k) const {
    int32_t v;
    if (k < 4 * nt_) v = d_.tets[k];
    else if ((k -= 4 * nt_) < 3 * nf_) v = d_.triangles[k];
    else v = d_.feature_edges[k - 3 * nf_];
    return v - d_.base;
}

uint64_t VtkCellWriter::end_offset(uint64_t c) const {
    if (c < nt_) return 4 * (c + 1);
    if (c < nt_ + nf_) return 4 * nt_ + 3 * (c - nt_ + 1);
    return 4 * nt_ + 3 * nf_ + 2 * (c - nt_ - nf_ + 1);
}

int32_t VtkCellWriter::marker(uint64_t c) const {
    if (c >= nt_ + nf_) return d_.edge_refs.empty() ? 0 : d_.edge_refs[c - nt_ - nf_];
    if (c >= nt_) return d_.tri_markers[c - nt_];
    return -1;  // on tets
}

double VtkCellWriter::field(const MeshData::TetField& f, uint64_t c) const {
    return c < nt_ ? f.values[c] : std::numeric_limits<double>::quiet_NaN();
}

std::vector<uint8_t> VtkCellWriter::flags(const std::vector<int32_t>& vertices) const {
    std::vector<uint8_t> flag(nv_, 0);
    for (int32_t v : vertices) flag[static_cast<size_t>(v - d_.base)] = 1;
    return flag;
}

}  // namespace bodt
