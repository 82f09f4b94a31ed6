// trace/capped_walks.hpp -- what a command says about walks cut short: a walk still on the surface after
// walk::WalkLimits::max_events facet events (or where no hit normal could be drawn) ends as `capped`, and the energy
// it would have carried out is missing from the estimate, which reads low by it.
//
// The sample estimator (trace, the report's walk section, the fitter's albedo points) carries a weight in [0, 1], so
// its capped walks hide at most capped / walks of the albedo; the eval estimator's (brdf, the fitter's eval points)
// next-event terms have no upper bound, so what its capped walks hide has none either. A result whose hidden part
// could exceed its own standard error is not an estimate: the commands refuse it (input_error, naming the item);
// below that they print a warning and keep the count (trace's meta.json capped_walks).
#pragma once

#include <cstdint>
#include <string>

#include "smithlab/walk/walk.hpp"

namespace smithlab::trace {

// "3 of 1000 walks were cut short (the cap: 1000000 facet events a walk)".
inline std::string capped_text(std::int64_t capped, std::int64_t walks) {
    return std::to_string(capped) + " of " + std::to_string(walks) +
        " walks were cut short (the cap: " + std::to_string(walk::WalkLimits{}.max_events) + " facet events a walk)";
}

// Whether what `capped` of `walks` sample-estimator walks may carry (at most 1 each) could exceed the standard error.
inline bool capped_beyond_error(std::int64_t capped, std::int64_t walks, double stderr_) {
    return capped > 0 && static_cast<double>(capped) / static_cast<double>(walks) > stderr_;
}

}  // namespace smithlab::trace
