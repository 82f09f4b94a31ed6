// Tracing the fitter's points on one microsurface: each point's walks split by diffuse events
// (smithlab/fit/dataset.hpp), by the eval estimator (f(wi, wo) |cos theta_o|) or the sample estimator (the directional
// albedo from wi).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/surface.hpp"
#include "smithlab/walk/facets.hpp"

namespace smithlab::fit {

// A point to trace: its directions (the albedo estimator reads wi only) and its random stream.
struct TracePoint {
    Vec3 wi, wo;
    std::uint64_t stream;
};
// How a point is traced: by the sample estimator (the directional albedo from wi), or by the eval estimator named
// (f(wi, wo) |cos theta_o|; walk.hpp).
struct Estimator {
    bool albedo = false;
    walk::EvalEstimator eval = fit_estimator;
};

// One point's split moments on a built microsurface, walk k from WalkRng(seed, point.stream, k).
fit::SplitMoments trace_point(const AnySurface& surface, const walk::Material& material, const TracePoint& point,
                              Estimator estimator, std::uint64_t seed, std::int64_t walks);

// The points' split moments on one microsurface, in parallel (a point per block, merged in point order: the same
// bits for any `threads`); done(k) once the first k points are merged.
std::vector<fit::SplitMoments> trace_points(const AnyNdf& ndf, const walk::Material& material,
                                            const std::vector<TracePoint>& points, Estimator estimator,
                                            std::uint64_t seed, std::int64_t walks, unsigned threads,
                                            const std::function<void(std::uint64_t)>& done);

}  // namespace smithlab::fit
