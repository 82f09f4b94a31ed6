// cluster/traffic.hpp -- what rank 0 of a run on several ranks saw (meta.json's "mpi" object: traffic_json.hpp).
#pragma once

#include <cstdint>

namespace smithlab::cluster {

// Rank 0's messages and bytes both ways, the blocks traced here and by the other ranks, the time its main thread
// spent serving messages (reading, merging, answering: the dispatcher's cost), and the time finishing jobs took (the
// plan's finish: writing cell files and caches), on whichever of its threads.
struct Traffic {
    std::int64_t messages = 0, bytes = 0;
    std::uint64_t blocks_here = 0, blocks_elsewhere = 0;
    double serving_seconds = 0.0, finishing_seconds = 0.0;
};

}  // namespace smithlab::cluster
