// The installed bodt.h on its own must compile as C++17:
// c++ -std=c++17 -pedantic -Wall -Wextra -Werror -c
#include <bodt.h>
#include <bodt.h>  // the include guard works

#include <type_traits>

static_assert(std::is_standard_layout<bodt_quality>::value, "bodt_quality is a C struct");
static_assert(std::is_standard_layout<bodt_step_report>::value, "bodt_step_report is a C struct");
static_assert(std::is_same<decltype(&bodt_mesh_create),
                           int (*)(int32_t, const double*, int32_t, const int32_t*, int, bodt_mesh**)>::value,
              "bodt_mesh_create has the documented signature");

int bodt_header_check();

int bodt_header_check() {
    bodt_quality quality{};
    bodt_step_report report{};
    quality.size = sizeof quality;
    report.size = sizeof report;
    bodt_step_callback callback = nullptr;
    return static_cast<int>(quality.size + report.size) + (callback == nullptr) + BODT_DIHEDRAL_BINS +
           BODT_VERSION_NUMBER + BODT_MODE_LAPLACE + BODT_ERR_UNSUPPORTED;
}
