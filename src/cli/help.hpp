// The manual pages of the bodt command: `bodt --help`, `bodt help CMD`,
// `bodt CMD --help`.
#pragma once

#include <string>

namespace bodt_cli {

// Prints the page of `command` ("" for the overview) on stdout; false for
// an unknown command.
bool print_help(const std::string& command);

}  // namespace bodt_cli
