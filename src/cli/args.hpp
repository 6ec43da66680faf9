// Command-line parsing for the bodt command: one option parser for every
// subcommand, and the tables of names it accepts (modes, operations, file
// formats, --param keys).
#pragma once

#include "bodt.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace bodt_cli {

// One option a subcommand accepts: "--name", an optional one-letter alias
// ("-q" or nullptr), and whether it takes a value ("--name VALUE" or
// "--name=VALUE").
struct OptionSpec {
    const char* name;
    const char* alias;
    bool takes_value;
};

// The options every subcommand takes: --help, --quiet, --verbose.
extern const OptionSpec kCommonOptions[3];

struct ParsedArgs {
    std::vector<std::string> positional;
    // In command-line order, under their long names; flags have value "".
    std::vector<std::pair<std::string, std::string>> options;

    bool has(const char* name) const;
    // The last value given for `name`, or nullptr.
    const std::string* last(const char* name) const;
    std::vector<std::string> all(const char* name) const;
};

// Parses `args` against `spec` plus kCommonOptions.  "--" ends the options.
// False with `error` set for an unknown option or a missing value.
bool parse_args(const std::vector<std::string>& args, const std::vector<OptionSpec>& spec, ParsedArgs& out,
                std::string& error);

enum class Verbosity { Quiet, Normal, Verbose };
// From --quiet / --verbose; false (with `error`) when both are given.
bool verbosity_of(const ParsedArgs& parsed, Verbosity& verbosity, std::string& error);

// --mode NAME -> enum bodt_mode.
bool parse_mode(const std::string& value, int& mode, std::string& error);
const char* mode_name(int mode);
// --ops LIST: "default" or comma-separated smooth, flip, insert, collapse.
bool parse_ops(const std::string& value, int32_t& ops, std::string& error);
// A BODT_PARAM_OPS value as --ops takes it: "default", or the names of its
// bits separated by commas ("none" for 0).
std::string ops_text(int32_t ops);
// --iterations N: a whole number from 1 to 1000000.
bool parse_iterations(const std::string& value, int32_t& iterations, std::string& error);

// --format NAME -> enum bodt_format (mesh, meshb, tetgen, gmsh, gmsh-binary,
// gmsh22, gmsh22-binary, vtu, abaqus).
bool parse_format(const std::string& value, int& format, std::string& error);

// --threads N: a whole number (the library checks its range).
bool parse_threads(const std::string& value, int32_t& threads, std::string& error);

// A --param k=v: k is a BODT_PARAM_* name in lower case without the prefix.
struct ParamInfo {
    const char* name;
    int key;
    bool is_int;
};
const std::vector<ParamInfo>& param_table();

struct ParamSetting {
    const ParamInfo* info = nullptr;
    int32_t int_value = 0;
    double double_value = 0.0;
};
// Parses "k=v"; the value's type (int or double) is the key's.  The error
// for an unknown key lists the valid keys.
bool parse_param(const std::string& text, ParamSetting& out, std::string& error);
// Sets the parameters on `mesh` in order; false with `error` (the library's
// message) for a value the library refuses (out of range).
bool apply_params(bodt_mesh* mesh, const std::vector<ParamSetting>& params, std::string& error);

}  // namespace bodt_cli
