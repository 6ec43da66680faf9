#include "common/parallel.hpp"

#include <cstdlib>
#include <thread>

namespace bodt {

int default_threads() {
    if (const char* env = std::getenv("OMP_NUM_THREADS")) {
        // "4" or "4,2" (OpenMP's nested list): the first number.
        char* end = nullptr;
        const long n = std::strtol(env, &end, 10);
        if (end != env && n > 0) return static_cast<int>(std::min(n, 1024L));
    }
    const unsigned cores = std::thread::hardware_concurrency();
    return cores > 0 ? static_cast<int>(std::min(cores, 1024U)) : 1;
}

}  // namespace bodt
