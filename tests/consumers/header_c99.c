/* The installed bodt.h on its own must compile as strict C99:
 * cc -std=c99 -pedantic -Wall -Wextra -Wstrict-prototypes -Werror -c */
#include <bodt.h>
#include <bodt.h> /* the include guard works */

int bodt_header_check(void);

int bodt_header_check(void) {
    bodt_quality quality = {0};
    bodt_step_report report = {0};
    bodt_step_callback callback = 0;
    int (*create)(int32_t, const double *, int32_t, const int32_t *, int, bodt_mesh **) = bodt_mesh_create;
    quality.size = sizeof quality;
    report.size = sizeof report;
    return (int)(quality.size + report.size) + (callback == 0) + (create != 0) + BODT_DIHEDRAL_BINS +
           BODT_VERSION_NUMBER + BODT_MODE_LAPLACE + BODT_PARAM_NEVER_WORSE + BODT_ERR_UNSUPPORTED;
}
