// The one exception type of the core.  It carries a bodt_status code and a
// message naming the offending entity; the C API turns it into a status and
// bodt_mesh_last_error(), so no exception ever crosses the library boundary.
#pragma once

#include <stdexcept>
#include <string>

namespace bodt {

class Error : public std::runtime_error {
public:
    Error(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
    int status() const { return status_; }

private:
    int status_;
};

}  // namespace bodt
