// The fitter's data for each NDF family: the points traced (or read back from the cache) for the training set, the
// validation set and the directional albedos, each point split by diffuse events (smithlab/fit/dataset.hpp).
//
// The sets' layout and random streams: fit/data_sets.hpp. Each group (one alpha of one set) is written to
// OUT/cache/NDF/SET-G.csv when traced (fit/point_cache.hpp: keyed by all that defines it, with its points'
// directions); a later run reuses a group whose key and directions match, so a killed run resumes from its last
// finished group and refitting traces nothing.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cluster/block_jobs.hpp"
#include "fit/fit_scene.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fit {

struct NdfData {
    FitFamily family;
    std::string label;  // "ggx", "gtr(gamma=1.5)"
    std::vector<fit::DataPoint> training, validation, albedo;
    std::vector<double> validation_alphas;  // the geometric midpoints of training.alpha
    std::int64_t traced = 0, reused = 0;    // points
    std::int64_t walks_traced = 0;
};

// What defines a fit scene's traced data (and its cache keys): the facets, the NDF families, the sets and the seed.
struct DataSpec {
    std::string material;
    std::vector<FitFamily> ndfs;
    FitScene::Training training;
    FitScene::Validation validation;
    std::uint64_t seed = 1;
    walk::EvalEstimator estimator = fit::fit_estimator;
};
DataSpec data_spec(const FitScene& scene);

// What tracing has done so far, for progress lines: points traced of points to trace.
using ProgressFn = std::function<void(std::int64_t done, std::int64_t total)>;

// The points of every NDF family of the scene, in its order. Checks every NDF (the registry's refusals name
// FILE:LINE: ndf.family) and builds each microsurface, then calls checked(), then reads the cache and traces what it
// lacks. Under MPI every rank calls it and traces (cluster/block_jobs.hpp); rank 0 reads and writes the cache and
// gets the data, the other ranks nothing. progress(points traced, points to trace).
// traffic: what rank 0 communicated, when given.
std::vector<NdfData> gather(const DataSpec& spec, const NdfRegistry& registry, const std::filesystem::path& cache,
                            unsigned threads, const ProgressFn& progress, const std::function<void()>& checked = {},
                            cluster::Traffic* traffic = nullptr);

}  // namespace smithlab::fit
