// Keys for faces and edges by their vertex indices, independent of the order
// the vertices come in.  Header-only and free of Eigen, so that the file
// readers and writers of src/io (whose fuzzers link only the io objects) use
// the same keys as the mesh.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace bodt {

// A face by its three vertex indices, sorted ascending.
struct FaceKey {
    std::array<int32_t, 3> v;
    static FaceKey of(int32_t a, int32_t b, int32_t c) {
        if (a > b) std::swap(a, b);
        if (b > c) std::swap(b, c);
        if (a > b) std::swap(a, b);
        return {{a, b, c}};
    }
    bool operator==(const FaceKey& o) const { return v == o.v; }
    bool operator<(const FaceKey& o) const { return v < o.v; }
};

struct FaceKeyHash {
    size_t operator()(const FaceKey& k) const {
        uint64_t h = static_cast<uint32_t>(k.v[0]);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k.v[1]);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k.v[2]);
        return static_cast<size_t>(h ^ (h >> 29));
    }
};

// An undirected edge as (smaller, larger) vertex index in one integer.
using EdgeKey = uint64_t;
inline EdgeKey edge_key(int32_t a, int32_t b) {
    if (a > b) std::swap(a, b);
    return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}
inline int32_t edge_first(EdgeKey k) { return static_cast<int32_t>(k >> 32); }
inline int32_t edge_second(EdgeKey k) { return static_cast<int32_t>(k & 0xffffffffu); }
using EdgeSet = std::unordered_set<EdgeKey>;
using EdgeRefs = std::unordered_map<EdgeKey, int32_t>;  // an edge and its reference number

}  // namespace bodt
