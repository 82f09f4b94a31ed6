// meta.json's "mpi" object of a run on several ranks: what rank 0 saw (cluster/traffic.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include "cluster/mpi_world.hpp"
#include "cluster/traffic.hpp"

namespace smithlab::cluster {

inline nlohmann::ordered_json traffic_json(const Traffic& t) {
    return {{"ranks", mpi::size()},
            {"messages", t.messages},
            {"bytes", t.bytes},
            {"blocks_rank0", t.blocks_here},
            {"blocks_other_ranks", t.blocks_elsewhere},
            {"rank0_serving_seconds", t.serving_seconds},
            {"rank0_finishing_seconds", t.finishing_seconds}};
}

}  // namespace smithlab::cluster
