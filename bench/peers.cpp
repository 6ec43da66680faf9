// peers.cpp -- see peers.hpp.
#include "peers.hpp"

#include "bench_util.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#ifndef BODT_BENCH_PEERS_DIR
#define BODT_BENCH_PEERS_DIR "bench/peers"
#endif
#ifndef BODT_BENCH_DEFAULT_PYTHON
#define BODT_BENCH_DEFAULT_PYTHON "/usr/bin/python3"
#endif

namespace bench {

namespace {

std::string python() {
    const char* p = std::getenv("BODT_BENCH_PYTHON");
    return p && *p ? p : BODT_BENCH_DEFAULT_PYTHON;
}

std::string gmsh_script() { return std::string(BODT_BENCH_PEERS_DIR) + "/gmsh_optimize.py"; }

const char* gmsh_method(PeerKind k) { return k == PeerKind::GmshNetgen ? "Netgen" : "default"; }

// "Optimization seconds:  0.0028" -> 0.0028; -1 when the line is missing.
double seconds_after(const std::string& text, const std::string& label) {
    const size_t p = text.find(label);
    if (p == std::string::npos) return -1;
    return std::strtod(text.c_str() + p + label.size(), nullptr);
}

// The last line of the Gmsh script's output that starts with "BODT_PEER ",
// without that prefix (a JSON object); "" if none.
std::string peer_line(const std::string& text) {
    const std::string tag = "BODT_PEER ";
    size_t p = text.rfind("\n" + tag);
    if (p == std::string::npos) {
        if (text.compare(0, tag.size(), tag) != 0) return "";
        p = 0;
    } else {
        p += 1;
    }
    const size_t e = text.find('\n', p);
    return text.substr(p + tag.size(), e == std::string::npos ? std::string::npos : e - p - tag.size());
}

// A string or number field of a flat JSON object (no escapes beyond \").
std::string json_field(const std::string& obj, const std::string& key) {
    const std::string k = "\"" + key + "\":";
    size_t p = obj.find(k);
    if (p == std::string::npos) return "";
    p += k.size();
    while (p < obj.size() && obj[p] == ' ') ++p;
    if (p < obj.size() && obj[p] == '"') {
        std::string out;
        for (size_t i = p + 1; i < obj.size() && obj[i] != '"'; ++i) {
            if (obj[i] == '\\' && i + 1 < obj.size()) ++i;
            out += obj[i];
        }
        return out;
    }
    const size_t e = obj.find_first_of(",}", p);
    return obj.substr(p, e == std::string::npos ? std::string::npos : e - p);
}

std::string tail_of(const std::string& text, size_t n) {
    std::string t = text.size() > n ? "..." + text.substr(text.size() - n) : text;
    for (char& c : t)
        if (c == '\n') c = ' ';
    return t;
}

}  // namespace

const char* peer_name(PeerKind k) {
    switch (k) {
        case PeerKind::TetGen: return "tetgen-rO9/7";
        case PeerKind::Gmsh: return "gmsh";
        case PeerKind::GmshNetgen: return "gmsh-netgen";
        default: return "";
    }
}

std::string peer_description(PeerKind k) {
    switch (k) {
        case PeerKind::TetGen:
            return std::string("TetGen 1.5.0's optimiser: `tetgen ") + kTetGenSwitches +
                   "` on the mesh written as .node/.ele/.face (time: its \"Optimization seconds\")";
        case PeerKind::Gmsh:
            return "Gmsh's default tet optimiser: gmsh.model.mesh.optimize(\"\", force=True) on the mesh written as "
                   ".msh 4.1 (time: that call)";
        case PeerKind::GmshNetgen:
            return "Gmsh's Netgen optimiser: gmsh.model.mesh.optimize(\"Netgen\", force=True) (time: that call)";
        default: return "";
    }
}

bool peer_available(PeerKind k, std::string& why, std::string& version) {
    if (k == PeerKind::TetGen) {
        const std::string exe = find_program("tetgen");
        if (exe.empty()) {
            why = "no tetgen command in PATH (Debian: apt-get install tetgen)";
            return false;
        }
        version = exe;
        return true;
    }
    if (!is_file(python())) {
        why = "no " + python() + " (set BODT_BENCH_PYTHON)";
        return false;
    }
    if (!is_file(gmsh_script())) {
        why = "no " + gmsh_script();
        return false;
    }
    std::string dir;
    if (!make_temp_dir("bodt-bench-peer", dir)) {
        why = "cannot make a temp dir";
        return false;
    }
    const ProcessRun r = run_process({python(), gmsh_script(), "--check"}, dir + "/check.txt", 60);
    const std::string line = peer_line(read_text_file(dir + "/check.txt"));
    remove_tree(dir);
    if (r.exit_code != 0 || json_field(line, "status") != "ok") {
        why = "the Gmsh Python module cannot be imported by " + python() + " (Debian: apt-get install python3-gmsh)";
        return false;
    }
    version = "gmsh " + json_field(line, "gmsh");
    return true;
}

PeerOutcome run_peer(PeerKind k, const bodt_mesh* input, const std::string& dir, double timeout_s) {
    PeerOutcome o;
    const bool tetgen = k == PeerKind::TetGen;
    const std::string in = dir + (tetgen ? "/in.ele" : "/in.msh");
    const int st = bodt_mesh_write_format(input, in.c_str(), tetgen ? BODT_FORMAT_TETGEN : BODT_FORMAT_GMSH);
    if (st != BODT_OK) {
        o.where = "bodt_mesh_write_format";
        o.message = errmsg(input, st);
        return o;
    }
    std::vector<std::string> argv;
    if (tetgen) {
        argv = {find_program("tetgen"), kTetGenSwitches, in};
        o.output_path = dir + "/in.1.ele";
    } else {
        o.output_path = dir + "/out.msh";
        argv = {python(), gmsh_script(), in, o.output_path, gmsh_method(k)};
    }
    for (const std::string& a : argv) o.command += (o.command.empty() ? "" : " ") + a;
    const std::string log = dir + "/peer.log";
    const ProcessRun r = run_process(argv, log, timeout_s);
    o.process_s = r.wall_s;
    o.peak_rss_mb = r.peak_rss_mb;
    const std::string text = read_text_file(log);
    if (!r.started) {
        o.where = "starting the peer";
        o.message = r.error;
        return o;
    }
    if (r.timed_out) {
        o.status = "timeout";
        o.where = "peer process";
        o.message = "killed after " + fmt("%.0f", timeout_s) + " s";
        return o;
    }
    if (r.signal) {
        o.status = "crashed";
        o.where = "peer process";
        o.message = "killed by signal " + std::to_string(r.signal) + ": " + tail_of(text, 300);
        return o;
    }
    if (tetgen) {
        if (r.exit_code != 0 || !is_file(o.output_path)) {
            o.where = "tetgen";
            o.message = "exit status " + std::to_string(r.exit_code) + ": " + tail_of(text, 400);
            return o;
        }
        o.refine_s = seconds_after(text, "Refinement seconds:");
        o.time_s = seconds_after(text, "Optimization seconds:");
        if (o.time_s >= 0) {
            o.time_source = "tetgen's Optimization seconds";
        } else {
            o.time_s = r.wall_s;
            o.time_source = "process wall time (tetgen printed no Optimization seconds)";
        }
        o.status = "ok";
        return o;
    }
    const std::string line = peer_line(text);
    const std::string status = json_field(line, "status");
    if (status == "unsupported") {
        o.status = "unsupported";
        o.where = "gmsh.model.mesh.optimize";
        o.message = json_field(line, "message");
        return o;
    }
    if (r.exit_code != 0 || status != "ok" || !is_file(o.output_path)) {
        o.where = "gmsh_optimize.py";
        o.message = "exit status " + std::to_string(r.exit_code) + ": " +
                    (line.empty() ? tail_of(text, 400) : json_field(line, "message"));
        return o;
    }
    o.time_s = std::strtod(json_field(line, "optimize_s").c_str(), nullptr);
    o.time_source = "the gmsh.model.mesh.optimize call";
    o.status = "ok";
    return o;
}

}  // namespace bench
