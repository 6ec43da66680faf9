// What the sweeps between two topology passes did, for the passes' memories
// of the attempts that failed (FailedFlips, StuckTets).
#pragma once

#include <cstdint>
#include <vector>

namespace bodt {

// When each vertex last moved, by the clock of the sweeps between passes
// (SettledVertices): a record from an earlier pass holds while none of its
// vertices moved after it.  A new epoch forgets every record.
struct SweepHistory {
    const std::vector<uint32_t>* moved_at;  // per vertex, 0: never; may be shorter (never)
    uint32_t now;
    uint64_t epoch;

    bool moved_after(int32_t v, uint32_t tick) const {
        return moved_at && static_cast<size_t>(v) < moved_at->size() && (*moved_at)[v] > tick;
    }
};

}  // namespace bodt
