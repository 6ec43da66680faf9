#include "pipeline/params.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace bodt {

namespace {

enum class Type { Int, Double };

struct Info {
    int key;
    const char* name;
    Type type;
    double lo, hi;  // valid range
    bool lo_open = false, hi_open = false;  // the range excludes lo / hi
};

constexpr Info kParams[] = {
    {BODT_PARAM_TOLERANCE, "BODT_PARAM_TOLERANCE", Type::Double, 0.0, 1.0},
    {BODT_PARAM_BACKTRACK_STEPS, "BODT_PARAM_BACKTRACK_STEPS", Type::Int, 0, 50},
    {BODT_PARAM_MIN_STRETCH, "BODT_PARAM_MIN_STRETCH", Type::Double, 0.0, 0.5},
    {BODT_PARAM_NEVER_WORSE, "BODT_PARAM_NEVER_WORSE", Type::Int, 0, 1},
    {BODT_PARAM_FEATURE_ANGLE, "BODT_PARAM_FEATURE_ANGLE", Type::Double, 0.0, 180.0},
    {BODT_PARAM_EDGE_RATIO, "BODT_PARAM_EDGE_RATIO", Type::Double, 0.0, 1.0},
    {BODT_PARAM_CORNER_RATIO, "BODT_PARAM_CORNER_RATIO", Type::Double, 0.0, 1.0},
    {BODT_PARAM_OPS, "BODT_PARAM_OPS", Type::Int, -1, BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT | BODT_OP_COLLAPSE},
    {BODT_PARAM_KEEP_SURFACE, "BODT_PARAM_KEEP_SURFACE", Type::Int, 0, 1},
    {BODT_PARAM_BAD_ANGLE, "BODT_PARAM_BAD_ANGLE", Type::Double, 0.0, 60.0},
    {BODT_PARAM_DELAUNAY_FLIPS, "BODT_PARAM_DELAUNAY_FLIPS", Type::Int, 0, 1},
    {BODT_PARAM_WEIGHT_C, "BODT_PARAM_WEIGHT_C", Type::Double, 0.0, 1.0},
    {BODT_PARAM_POOR_QUALITY, "BODT_PARAM_POOR_QUALITY", Type::Double, 0.0, 1.0},
    {BODT_PARAM_QN_EPSILON, "BODT_PARAM_QN_EPSILON", Type::Double, 1e-12, 1.0},
    {BODT_PARAM_QN_MAX_ITERATIONS, "BODT_PARAM_QN_MAX_ITERATIONS", Type::Int, 1, 1000},
    {BODT_PARAM_QN_INITIAL_STEP, "BODT_PARAM_QN_INITIAL_STEP", Type::Double, 1e-6, 10.0},
    {BODT_PARAM_QN_INTERVAL_GROWTH, "BODT_PARAM_QN_INTERVAL_GROWTH", Type::Double, 1.1, 10.0},
    {BODT_PARAM_ODT_STEP, "BODT_PARAM_ODT_STEP", Type::Double, 0.0, 1.0, true, false},
    {BODT_PARAM_DENSITY_SPLIT, "BODT_PARAM_DENSITY_SPLIT", Type::Double, 0.0, 1.0, true, true},
    {BODT_PARAM_DENSITY_COLLAPSE, "BODT_PARAM_DENSITY_COLLAPSE", Type::Double, 1.0, 100.0, true, false},
    {BODT_PARAM_FIT_TOLERANCE, "BODT_PARAM_FIT_TOLERANCE", Type::Double, 0.0, 0.1, true, false},
    {BODT_PARAM_THREADS, "BODT_PARAM_THREADS", Type::Int, 0, 1024},
    {BODT_PARAM_ASCENT_ANGLE, "BODT_PARAM_ASCENT_ANGLE", Type::Double, 0.0, 60.0},
};

const Info& lookup(int key, Type want) {
    for (const Info& info : kParams) {
        if (info.key != key) continue;
        if (info.type != want)
            throw Error(BODT_ERR_INVALID_ARGUMENT,
                        std::string(info.name) + " is " + (info.type == Type::Int ? "an int" : "a double") +
                            " parameter: use bodt_" + (want == Type::Int ? "set/get_param_double" : "set/get_param_int"));
        return info;
    }
    throw Error(BODT_ERR_INVALID_ARGUMENT, "unknown parameter key " + std::to_string(key));
}

std::string show(const Info& info, double value) {
    if (info.type == Type::Int) return std::to_string(static_cast<long long>(value));
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

void check_range(const Info& info, double value) {
    const bool above = info.lo_open ? value > info.lo : value >= info.lo;
    const bool below = info.hi_open ? value < info.hi : value <= info.hi;
    if (!(above && below))
        throw Error(BODT_ERR_INVALID_ARGUMENT, std::string(info.name) + " must be in " + (info.lo_open ? "(" : "[") +
                                                   show(info, info.lo) + ", " + show(info, info.hi) +
                                                   (info.hi_open ? ")" : "]") + ", got " + show(info, value));
}

// The member behind an int key (already looked up).
int32_t& int_field(Params& p, int key) {
    switch (key) {
        case BODT_PARAM_BACKTRACK_STEPS: return p.backtrack_steps;
        case BODT_PARAM_OPS: return p.ops;
        case BODT_PARAM_KEEP_SURFACE: return p.keep_surface;
        case BODT_PARAM_DELAUNAY_FLIPS: return p.delaunay_flips;
        case BODT_PARAM_QN_MAX_ITERATIONS: return p.qn_max_iterations;
        case BODT_PARAM_THREADS: return p.threads;
        default: return p.never_worse;
    }
}

// The member behind a double key (already looked up).
double& double_field(Params& p, int key) {
    switch (key) {
        case BODT_PARAM_TOLERANCE: return p.tolerance;
        case BODT_PARAM_MIN_STRETCH: return p.min_stretch;
        case BODT_PARAM_FEATURE_ANGLE: return p.feature_angle;
        case BODT_PARAM_EDGE_RATIO: return p.edge_ratio;
        case BODT_PARAM_BAD_ANGLE: return p.bad_angle;
        case BODT_PARAM_WEIGHT_C: return p.weight_c;
        case BODT_PARAM_POOR_QUALITY: return p.poor_quality;
        case BODT_PARAM_QN_EPSILON: return p.qn_epsilon;
        case BODT_PARAM_QN_INITIAL_STEP: return p.qn_initial_step;
        case BODT_PARAM_QN_INTERVAL_GROWTH: return p.qn_growth;
        case BODT_PARAM_ODT_STEP: return p.odt_step;
        case BODT_PARAM_DENSITY_SPLIT: return p.density_split;
        case BODT_PARAM_DENSITY_COLLAPSE: return p.density_collapse;
        case BODT_PARAM_FIT_TOLERANCE: return p.fit_tolerance;
        case BODT_PARAM_ASCENT_ANGLE: return p.ascent_angle;
        default: return p.corner_ratio;
    }
}

}  // namespace

void set_param_int(Params& p, int key, int32_t value) {
    check_range(lookup(key, Type::Int), value);
    int_field(p, key) = value;
}

void set_param_double(Params& p, int key, double value) {
    check_range(lookup(key, Type::Double), value);
    double_field(p, key) = value;
}

int32_t get_param_int(const Params& p, int key) {
    lookup(key, Type::Int);
    return int_field(const_cast<Params&>(p), key);
}

double get_param_double(const Params& p, int key) {
    lookup(key, Type::Double);
    return double_field(const_cast<Params&>(p), key);
}

}  // namespace bodt
