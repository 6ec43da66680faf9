// The tunable parameters of a mesh handle, keyed by the bodt_param enum.
#pragma once

#include <cstdint>

namespace bodt {

struct Params {
    double tolerance = 1e-6;       // BODT_PARAM_TOLERANCE
    int32_t backtrack_steps = 4;   // BODT_PARAM_BACKTRACK_STEPS
    double min_stretch = 1e-3;     // BODT_PARAM_MIN_STRETCH
    int32_t never_worse = 1;       // BODT_PARAM_NEVER_WORSE
    double feature_angle = 30.0;   // BODT_PARAM_FEATURE_ANGLE, degrees
    double edge_ratio = 0.2;       // BODT_PARAM_EDGE_RATIO
    double corner_ratio = 0.2;     // BODT_PARAM_CORNER_RATIO
    int32_t ops = -1;              // BODT_PARAM_OPS: bodt_op bits, -1 the mode's default
    int32_t keep_surface = 0;      // BODT_PARAM_KEEP_SURFACE
    double bad_angle = 15.0;       // BODT_PARAM_BAD_ANGLE, degrees
    int32_t delaunay_flips = 0;    // BODT_PARAM_DELAUNAY_FLIPS
    double weight_c = 0.75;        // BODT_PARAM_WEIGHT_C
    double poor_quality = 0.5;     // BODT_PARAM_POOR_QUALITY
    double qn_epsilon = 1e-3;      // BODT_PARAM_QN_EPSILON
    int32_t qn_max_iterations = 10;   // BODT_PARAM_QN_MAX_ITERATIONS
    double qn_initial_step = 0.05; // BODT_PARAM_QN_INITIAL_STEP
    double qn_growth = 2.0;        // BODT_PARAM_QN_INTERVAL_GROWTH
    double odt_step = 1.0;         // BODT_PARAM_ODT_STEP (alpha, paper 002 eq. 3.4)
    double density_split = 2.0 / 3.0;   // BODT_PARAM_DENSITY_SPLIT (gamma, sec. 3.5.1)
    double density_collapse = 1.5;      // BODT_PARAM_DENSITY_COLLAPSE (delta)
    double fit_tolerance = 1e-5;   // BODT_PARAM_FIT_TOLERANCE
    int32_t threads = 1;           // BODT_PARAM_THREADS: 0 = default_threads()
    double ascent_angle = 30.0;    // BODT_PARAM_ASCENT_ANGLE, degrees (0: off)
};

// Each throws Error(BODT_ERR_INVALID_ARGUMENT) for an unknown key, a key of
// the other type, or a value out of the key's range.
void set_param_int(Params& p, int key, int32_t value);
void set_param_double(Params& p, int key, double value);
int32_t get_param_int(const Params& p, int key);
double get_param_double(const Params& p, int key);

}  // namespace bodt
