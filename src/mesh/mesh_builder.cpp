#include "mesh/mesh_builder.hpp"

#include "bodt.h"
#include "common/error.hpp"
#include "mesh/curve_order.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace bodt {

namespace {

// "3 tets are inverted: 4, 9, 11" with at most ten entries listed.
std::string list_offenders(const std::vector<int32_t>& ids, int base) {
    std::string s;
    const size_t shown = std::min<size_t>(ids.size(), 10);
    for (size_t k = 0; k < shown; ++k) s += (k ? ", " : "") + std::to_string(ids[k] + base);
    if (ids.size() > shown) s += ", ...";
    return s;
}

constexpr double kMaxCoordinate = 1e30;

std::string format_double(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

std::string plural(size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

void check_arguments(const MeshArrays& in) {
    if (in.index_base != 0 && in.index_base != 1)
        throw Error(BODT_ERR_INVALID_ARGUMENT, "index_base must be 0 or 1, got " + std::to_string(in.index_base));
    if (in.nverts <= 0)
        throw Error(BODT_ERR_INVALID_ARGUMENT, "nverts must be positive, got " + std::to_string(in.nverts));
    if (in.ntets <= 0)
        throw Error(BODT_ERR_INVALID_ARGUMENT, "ntets must be positive, got " + std::to_string(in.ntets));
    if (!in.xyz) throw Error(BODT_ERR_INVALID_ARGUMENT, "xyz is NULL");
    if (!in.tets) throw Error(BODT_ERR_INVALID_ARGUMENT, "tets is NULL");
    if (in.flags & ~static_cast<uint32_t>(BODT_CREATE_ACCEPT_INVERTED | BODT_CREATE_KEEP_ORDER))
        throw Error(BODT_ERR_INVALID_ARGUMENT, "unknown create flags " + std::to_string(in.flags));
}

void copy_points(const MeshArrays& in, TetMesh& mesh) {
    static const char* axis[3] = {"x", "y", "z"};
    mesh.points.resize(static_cast<size_t>(in.nverts));
    for (int32_t v = 0; v < in.nverts; ++v) {
        for (int k = 0; k < 3; ++k) {
            const double c = in.xyz[3 * static_cast<size_t>(v) + k];
            if (!std::isfinite(c))
                throw Error(BODT_ERR_BAD_MESH, "vertex " + std::to_string(v + in.index_base) +
                                                   " has a non-finite coordinate (" + axis[k] + " = " +
                                                   std::to_string(c) + ")");
            // The quality measures multiply up to eight coordinate
            // differences (a dihedral angle's two squared face normals).
            if (std::abs(c) > kMaxCoordinate)
                throw Error(BODT_ERR_BAD_MESH, "vertex " + std::to_string(v + in.index_base) + " has a coordinate (" +
                                                   axis[k] + " = " + format_double(c) +
                                                   ") beyond 1e30, where the quality measures overflow");
            mesh.points[v][k] = c;
        }
    }
}

void copy_tets(const MeshArrays& in, TetMesh& mesh) {
    mesh.tets.resize(static_cast<size_t>(in.ntets));
    for (int32_t t = 0; t < in.ntets; ++t) {
        Tet q;
        for (int k = 0; k < 4; ++k) {
            const int32_t raw = in.tets[4 * static_cast<size_t>(t) + k];
            const int64_t v = static_cast<int64_t>(raw) - in.index_base;
            if (v < 0 || v >= in.nverts)
                throw Error(BODT_ERR_BAD_MESH, "tet " + std::to_string(t + in.index_base) + " uses vertex " +
                                                   std::to_string(raw) + ", but the mesh has " +
                                                   std::to_string(in.nverts) + " vertices" +
                                                   (in.index_base ? " (numbered from 1)" : " (numbered from 0)"));
            q[k] = static_cast<int32_t>(v);
            for (int j = 0; j < k; ++j)
                if (q[j] == q[k])
                    throw Error(BODT_ERR_BAD_MESH, "tet " + std::to_string(t + in.index_base) + " uses vertex " +
                                                       std::to_string(raw) + " twice");
        }
        mesh.tets[t] = q;
    }
}

// Detects the caller's orientation convention (the majority's), stores every
// tet positively oriented in it, and refuses flat and (without the flag)
// inverted tets.
void normalise_orientation(const MeshArrays& in, BuiltMesh& out) {
    TetMesh& mesh = out.mesh;
    std::vector<int8_t> sign(mesh.tets.size());
    int64_t positive = 0, negative = 0;
    std::vector<int32_t> flat;
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        const auto p = mesh.tet_points(t);
        sign[t] = static_cast<int8_t>(orient(p[0], p[1], p[2], p[3]).sign);
        if (sign[t] > 0) ++positive;
        else if (sign[t] < 0) ++negative;
        else flat.push_back(t);
    }
    if (!flat.empty())
        throw Error(BODT_ERR_BAD_MESH, plural(flat.size(), "tet has", "tets have") +
                                           " zero volume (flat within round-off): " +
                                           list_offenders(flat, in.index_base));
    out.flipped = negative > positive;
    std::vector<int32_t> inverted;
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        if (out.flipped) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
        if ((sign[t] > 0) == out.flipped) inverted.push_back(t);
    }
    if (!inverted.empty() && !(in.flags & BODT_CREATE_ACCEPT_INVERTED))
        throw Error(BODT_ERR_BAD_MESH, plural(inverted.size(), "tet is", "tets are") +
                                           " inverted (oriented against the other " +
                                           std::to_string(mesh.tets.size() - inverted.size()) +
                                           "): " + list_offenders(inverted, in.index_base) +
                                           "; BODT_CREATE_ACCEPT_INVERTED accepts them");
    out.num_inverted = static_cast<int32_t>(inverted.size());
}

// Two positively oriented tets that share a face must lie on its two sides,
// which shows as the shared face having opposite orientations in them.
void check_sides(const TetMesh& mesh, int base) {
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        const auto pt = mesh.tet_points(t);
        if (orient(pt[0], pt[1], pt[2], pt[3]).sign <= 0) continue;
        for (int i = 0; i < 4; ++i) {
            const int32_t s = mesh.neighbors[t][i];
            if (s < t) continue;
            const auto ps = mesh.tet_points(s);
            if (orient(ps[0], ps[1], ps[2], ps[3]).sign <= 0) continue;
            int j = 0;
            while (mesh.neighbors[s][j] != t) ++j;
            // Opposite vertices on the same side of the shared face?
            const Tet& a = mesh.tets[t];
            const Vec3& f0 = mesh.points[a[kFaceVertex[i][0]]];
            const Vec3& f1 = mesh.points[a[kFaceVertex[i][1]]];
            const Vec3& f2 = mesh.points[a[kFaceVertex[i][2]]];
            const int side_t = orient(f0, f1, f2, mesh.points[a[i]]).sign;
            const int side_s = orient(f0, f1, f2, mesh.points[mesh.tets[s][j]]).sign;
            if (side_t == side_s)
                throw Error(BODT_ERR_BAD_MESH, "tets " + std::to_string(t + base) + " and " +
                                                   std::to_string(s + base) +
                                                   " lie on the same side of their shared face: the mesh overlaps "
                                                   "itself");
        }
    }
}

// The mesh as `in` gives it (already checked), the caller's numbering
// being `caller`: the topology is built in it.
BuiltMesh build_as_given(const MeshArrays& in, CallerNumbering caller) {
    BuiltMesh out;
    out.mesh.caller = std::move(caller);
    copy_points(in, out.mesh);
    copy_tets(in, out.mesh);
    normalise_orientation(in, out);
    out.mesh.regions.assign(out.mesh.tets.size(), 0);
    out.mesh.build_topology(in.index_base);
    if (out.num_inverted > 0) out.mesh.find_reversed_tets(in.index_base);
    check_sides(out.mesh, in.index_base);
    out.surfaces.build(out.mesh, in.index_base, BoundarySurface::Strictness::Strict);  // the domain boundary
    return out;
}

}  // namespace

void check_vertex_index(int32_t value, int32_t nverts, int base, const char* what, int64_t item) {
    const int64_t v = static_cast<int64_t>(value) - base;
    if (v < 0 || v >= nverts)
        throw Error(BODT_ERR_INVALID_ARGUMENT, std::string(what) + " " + std::to_string(item + base) +
                                                   " uses vertex " + std::to_string(value) + ", but the mesh has " +
                                                   std::to_string(nverts) + " vertices" +
                                                   (base ? " (numbered from 1)" : " (numbered from 0)"));
}

BuiltMesh build_mesh(const MeshArrays& in) {
    check_arguments(in);
    return build_as_given(in, {});
}

BuiltMesh build_mesh_in_curve_order(const MeshArrays& in) {
    check_arguments(in);
    CallerNumbering numbering = curve_order(in.nverts, in.xyz, in.ntets, in.tets, in.index_base);
    if (numbering.is_identity()) return build_as_given(in, {});
    try {
        std::vector<double> xyz;
        std::vector<int32_t> tets;
        renumber_input(numbering, in.xyz, in.tets, in.index_base, xyz, tets);
        MeshArrays renumbered = in;
        renumbered.xyz = xyz.data();
        renumbered.tets = tets.data();
        return build_as_given(renumbered, std::move(numbering));
    } catch (const Error&) {
        // Refused: built again in the caller's order, so that the message
        // names their vertices and tets (and, should a check depend on the
        // order, the mesh is kept as given).
    }
    return build_as_given(in, {});
}

}  // namespace bodt
