// peers.hpp -- the other tet-mesh optimisers bodt_bench runs on the same
// inputs: TetGen's (the tetgen command, Debian's tetgen 1.5.0) and Gmsh's
// (gmsh.model.mesh.optimize through bench/peers/gmsh_optimize.py and
// Debian's python3-gmsh).  The input is written with bodt_mesh_write_format,
// the peer runs as a separate process, and its output file is read back
// with bodt_mesh_read by the caller, which measures it with the very code
// that measures libbodt's runs.
#ifndef BODT_BENCH_PEERS_HPP
#define BODT_BENCH_PEERS_HPP

#include "bodt.h"

#include <string>

namespace bench {

enum class PeerKind { None = 0, TetGen, Gmsh, GmshNetgen };

// TetGen 1.5.0 runs its optimiser (optimizemesh) only together with -q: a
// bare `-rO9/7` reconstructs the mesh and writes it unchanged.  A radius-edge
// bound of 1000 with no dihedral bound keeps the Delaunay refinement that -q
// starts from splitting anything but degenerate tets.
constexpr const char* kTetGenSwitches = "-rq1000/0O9/7";

// Variant names, as in --modes and the tables.
const char* peer_name(PeerKind k);
// One line: what the peer runs.
std::string peer_description(PeerKind k);

// Whether the peer can run here; why not otherwise (a note for the summary)
// and its version when it can.
bool peer_available(PeerKind k, std::string& why, std::string& version);

struct PeerOutcome {
    std::string status = "error";   // ok, unsupported, error, timeout, crashed
    std::string where, message;
    std::string output_path;        // the optimised mesh, for bodt_mesh_read
    std::string command;            // as run
    double time_s = -1;             // the peer's own optimisation time (time_source), -1 unknown
    std::string time_source;        // what time_s is
    double refine_s = -1;           // TetGen: its "Refinement seconds" (-q), -1 unknown
    double process_s = 0;           // wall time of the whole process
    double peak_rss_mb = 0;         // of the peer process
};

// Writes `input` into dir (which exists), runs the peer with a timeout, and
// says where its output is.
PeerOutcome run_peer(PeerKind k, const bodt_mesh* input, const std::string& dir, double timeout_s);

}  // namespace bench

#endif
