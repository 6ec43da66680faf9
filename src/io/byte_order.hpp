// Unsigned integers as binary mesh files store them (.meshb, binary legacy
// .vtk, .vtu arrays): `size` bytes (1 to 8) in the file's byte order.  Read
// byte by byte, so the host's byte order and the value's alignment do not
// matter.
#pragma once

#include <cstdint>

namespace bodt {

inline uint64_t load_uint(const unsigned char* p, int size, bool big_endian) {
    uint64_t v = 0;
    for (int k = 0; k < size; ++k) v = (v << 8) | p[big_endian ? k : size - 1 - k];
    return v;
}

}  // namespace bodt
