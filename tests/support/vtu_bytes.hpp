// Bytes of VTU binary arrays for the VTU reader tests (test_io_vtu,
// test_io_vtu_compressed): the tests' own base64 encoder and decoder
// (independent of the reader's) and little-endian values.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace io_test {

inline std::string b64(const std::vector<uint8_t>& bytes) {
    static const char* a = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t k = 0; k < bytes.size(); k += 3) {
        const uint32_t b0 = bytes[k], b1 = k + 1 < bytes.size() ? bytes[k + 1] : 0u,
                       b2 = k + 2 < bytes.size() ? bytes[k + 2] : 0u;
        const uint32_t g = (b0 << 16) | (b1 << 8) | b2;
        out += a[(g >> 18) & 63];
        out += a[(g >> 12) & 63];
        out += k + 1 < bytes.size() ? a[(g >> 6) & 63] : '=';
        out += k + 2 < bytes.size() ? a[g & 63] : '=';
    }
    return out;
}

inline std::vector<uint8_t> unb64(const std::string& s) {
    std::vector<uint8_t> out;
    uint32_t g = 0;
    int n = 0, pad = 0;
    for (char c : s) {
        int v;
        if (c >= 'A' && c <= 'Z') v = c - 'A';
        else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
        else if (c >= '0' && c <= '9') v = c - '0' + 52;
        else if (c == '+') v = 62;
        else if (c == '/') v = 63;
        else if (c == '=') v = 0, ++pad;
        else continue;
        g = (g << 6) | static_cast<uint32_t>(v);
        if (++n == 4) {
            out.push_back(static_cast<uint8_t>(g >> 16));
            if (pad < 2) out.push_back(static_cast<uint8_t>(g >> 8));
            if (pad < 1) out.push_back(static_cast<uint8_t>(g));
            n = pad = 0;
            g = 0;
        }
    }
    return out;
}

template <class T>
inline void put_le(std::vector<uint8_t>& out, T value) {
    uint8_t b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));  // the tests check in main that the machine is little-endian
    out.insert(out.end(), b, b + sizeof(T));
}

}  // namespace io_test
