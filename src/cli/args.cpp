#include "cli/args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace bodt_cli {

const OptionSpec kCommonOptions[3] = {{"--help", "-h", false}, {"--quiet", "-q", false}, {"--verbose", "-v", false}};

bool ParsedArgs::has(const char* name) const {
    for (const auto& o : options)
        if (o.first == name) return true;
    return false;
}

const std::string* ParsedArgs::last(const char* name) const {
    const std::string* found = nullptr;
    for (const auto& o : options)
        if (o.first == name) found = &o.second;
    return found;
}

std::vector<std::string> ParsedArgs::all(const char* name) const {
    std::vector<std::string> values;
    for (const auto& o : options)
        if (o.first == name) values.push_back(o.second);
    return values;
}

bool parse_args(const std::vector<std::string>& args, const std::vector<OptionSpec>& spec, ParsedArgs& out,
                std::string& error) {
    std::vector<OptionSpec> known(spec);
    known.insert(known.end(), std::begin(kCommonOptions), std::end(kCommonOptions));
    bool options_done = false;
    for (size_t k = 0; k < args.size(); ++k) {
        const std::string& a = args[k];
        if (options_done || a.size() < 2 || a[0] != '-') {
            out.positional.push_back(a);
            continue;
        }
        if (a == "--") {
            options_done = true;
            continue;
        }
        const size_t eq = a.rfind("--", 0) == 0 ? a.find('=') : std::string::npos;
        const std::string name = a.substr(0, eq);
        const OptionSpec* found = nullptr;
        for (const OptionSpec& o : known)
            if (name == o.name || (o.alias && name == o.alias)) found = &o;
        if (!found) {
            error = "unknown option " + name;
            return false;
        }
        std::string value;
        if (found->takes_value) {
            if (eq != std::string::npos) {
                value = a.substr(eq + 1);
            } else if (k + 1 < args.size()) {
                value = args[++k];
            } else {
                error = std::string(found->name) + " needs a value";
                return false;
            }
        } else if (eq != std::string::npos) {
            error = std::string(found->name) + " takes no value";
            return false;
        }
        out.options.emplace_back(found->name, value);
    }
    return true;
}

bool verbosity_of(const ParsedArgs& parsed, Verbosity& verbosity, std::string& error) {
    const bool quiet = parsed.has("--quiet"), verbose = parsed.has("--verbose");
    if (quiet && verbose) {
        error = "--quiet and --verbose exclude each other";
        return false;
    }
    verbosity = quiet ? Verbosity::Quiet : verbose ? Verbosity::Verbose : Verbosity::Normal;
    return true;
}

namespace {

struct Named {
    const char* name;
    int value;
};

constexpr Named kModes[] = {{"bodt", BODT_MODE_BODT},       {"bodt-basic", BODT_MODE_BODT_BASIC},
                            {"odt", BODT_MODE_ODT},         {"laplace", BODT_MODE_LAPLACE},
                            {"opt-weighted", BODT_MODE_OPT_WEIGHTED}, {"phased", BODT_MODE_PHASED_ODT},
                            {"nodt", BODT_MODE_NODT}};

constexpr Named kOps[] = {
    {"smooth", BODT_OP_SMOOTH}, {"flip", BODT_OP_FLIP}, {"insert", BODT_OP_INSERT}, {"collapse", BODT_OP_COLLAPSE}};

constexpr Named kFormats[] = {{"mesh", BODT_FORMAT_MEDIT},
                              {"meshb", BODT_FORMAT_MEDIT_BINARY},
                              {"tetgen", BODT_FORMAT_TETGEN},
                              {"gmsh", BODT_FORMAT_GMSH},
                              {"gmsh-binary", BODT_FORMAT_GMSH_BINARY},
                              {"gmsh22", BODT_FORMAT_GMSH22},
                              {"gmsh22-binary", BODT_FORMAT_GMSH22_BINARY},
                              {"vtu", BODT_FORMAT_VTU},
                              {"vtk", BODT_FORMAT_VTK},
                              {"abaqus", BODT_FORMAT_ABAQUS}};

template <size_t N>
std::string names_of(const Named (&table)[N]) {
    std::string s;
    for (size_t k = 0; k < N; ++k) s += (k ? ", " : "") + std::string(table[k].name);
    return s;
}

template <size_t N>
const Named* find(const Named (&table)[N], const std::string& name) {
    for (const Named& n : table)
        if (name == n.name) return &n;
    return nullptr;
}

bool parse_int32(const std::string& text, int32_t& value) {
    if (text.empty()) return false;
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (*end != '\0' || errno == ERANGE || v < INT32_MIN || v > INT32_MAX) return false;
    value = static_cast<int32_t>(v);
    return true;
}

bool parse_double(const std::string& text, double& value) {
    if (text.empty()) return false;
    errno = 0;
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return *end == '\0' && errno != ERANGE && std::isfinite(value);
}

}  // namespace

bool parse_mode(const std::string& value, int& mode, std::string& error) {
    const Named* m = find(kModes, value);
    if (!m) {
        error = "unknown mode '" + value + "' (known: " + names_of(kModes) + ")";
        return false;
    }
    mode = m->value;
    return true;
}

const char* mode_name(int mode) {
    for (const Named& m : kModes)
        if (m.value == mode) return m.name;
    return "?";
}

bool parse_ops(const std::string& value, int32_t& ops, std::string& error) {
    if (value == "default") {
        ops = BODT_OPS_MODE_DEFAULT;
        return true;
    }
    ops = 0;
    size_t start = 0;
    while (true) {
        const size_t comma = value.find(',', start);
        const std::string item = value.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const Named* op = find(kOps, item);
        if (!op) {
            error = "--ops: unknown operation '" + item + "' (known: " + names_of(kOps) +
                    ", separated by commas; or default alone)";
            return false;
        }
        ops |= op->value;
        if (comma == std::string::npos) return true;
        start = comma + 1;
    }
}

std::string ops_text(int32_t ops) {
    if (ops == BODT_OPS_MODE_DEFAULT) return "default";
    std::string text;
    for (const Named& op : kOps)
        if (ops & op.value) text += (text.empty() ? "" : ",") + std::string(op.name);
    return text.empty() ? "none" : text;
}

bool parse_threads(const std::string& value, int32_t& threads, std::string& error) {
    if (!parse_int32(value, threads)) {
        error = "--threads: '" + value + "' is not a whole number (0: every core)";
        return false;
    }
    return true;
}

bool parse_iterations(const std::string& value, int32_t& iterations, std::string& error) {
    if (!parse_int32(value, iterations) || iterations < 1 || iterations > 1000000) {
        error = "--iterations must be a whole number from 1 to 1000000";
        return false;
    }
    return true;
}

bool parse_format(const std::string& value, int& format, std::string& error) {
    const Named* f = find(kFormats, value);
    if (!f) {
        error = "unknown format '" + value + "' (known: " + names_of(kFormats) + ")";
        return false;
    }
    format = f->value;
    return true;
}

const std::vector<ParamInfo>& param_table() {
    // The keys and types of enum bodt_param (bodt.h), in its order.
    static const std::vector<ParamInfo> table = {
        {"tolerance", BODT_PARAM_TOLERANCE, false},
        {"backtrack_steps", BODT_PARAM_BACKTRACK_STEPS, true},
        {"min_stretch", BODT_PARAM_MIN_STRETCH, false},
        {"never_worse", BODT_PARAM_NEVER_WORSE, true},
        {"feature_angle", BODT_PARAM_FEATURE_ANGLE, false},
        {"edge_ratio", BODT_PARAM_EDGE_RATIO, false},
        {"corner_ratio", BODT_PARAM_CORNER_RATIO, false},
        {"ops", BODT_PARAM_OPS, true},
        {"keep_surface", BODT_PARAM_KEEP_SURFACE, true},
        {"bad_angle", BODT_PARAM_BAD_ANGLE, false},
        {"delaunay_flips", BODT_PARAM_DELAUNAY_FLIPS, true},
        {"weight_c", BODT_PARAM_WEIGHT_C, false},
        {"poor_quality", BODT_PARAM_POOR_QUALITY, false},
        {"qn_epsilon", BODT_PARAM_QN_EPSILON, false},
        {"qn_max_iterations", BODT_PARAM_QN_MAX_ITERATIONS, true},
        {"qn_initial_step", BODT_PARAM_QN_INITIAL_STEP, false},
        {"qn_interval_growth", BODT_PARAM_QN_INTERVAL_GROWTH, false},
        {"odt_step", BODT_PARAM_ODT_STEP, false},
        {"density_split", BODT_PARAM_DENSITY_SPLIT, false},
        {"density_collapse", BODT_PARAM_DENSITY_COLLAPSE, false},
        {"fit_tolerance", BODT_PARAM_FIT_TOLERANCE, false},
        {"threads", BODT_PARAM_THREADS, true},
        {"ascent_angle", BODT_PARAM_ASCENT_ANGLE, false},
    };
    return table;
}

bool parse_param(const std::string& text, ParamSetting& out, std::string& error) {
    const size_t eq = text.find('=');
    const std::string key = text.substr(0, eq);
    out.info = nullptr;
    for (const ParamInfo& p : param_table())
        if (key == p.name) out.info = &p;
    if (!out.info) {
        std::string keys;
        for (const ParamInfo& p : param_table()) keys += (keys.empty() ? "" : ", ") + std::string(p.name);
        error = "--param: unknown key '" + key + "' (known: " + keys + ")";
        return false;
    }
    if (eq == std::string::npos) {
        error = "--param " + key + ": give a value, as in --param " + key + "=VALUE";
        return false;
    }
    const std::string value = text.substr(eq + 1);
    const bool ok = out.info->is_int ? parse_int32(value, out.int_value) : parse_double(value, out.double_value);
    if (!ok) {
        error = "--param " + key + ": '" + value + "' is not " + (out.info->is_int ? "a whole number" : "a number");
        return false;
    }
    return true;
}

bool apply_params(bodt_mesh* mesh, const std::vector<ParamSetting>& params, std::string& error) {
    for (const ParamSetting& p : params) {
        const int status = p.info->is_int ? bodt_set_param_int(mesh, p.info->key, p.int_value)
                                          : bodt_set_param_double(mesh, p.info->key, p.double_value);
        if (status != BODT_OK) {
            error = std::string("--param ") + p.info->name + ": " + bodt_mesh_last_error(mesh);
            return false;
        }
    }
    return true;
}

}  // namespace bodt_cli
