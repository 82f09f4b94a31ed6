// The fitter's data for one NDF family: the points traced (or read back from the cache) for the training set, the
// validation set and the directional albedos, each point split by diffuse events (smithlab/fit/dataset.hpp).
//
// Point j of group g (one alpha of one set) of NDF n draws its walks from WalkRng(seed, stream, k), stream =
// set << 48 | n << 32 | g << 16 | j: the same bits for any --threads, resumed or not. Each group is written to
// OUT/cache/NDF/SET-G.csv when traced, under a key of all that defines it (version, NDF spec, material, walks, seed,
// stream) with its points' directions; a later run reuses a group whose key and directions match, so a killed run
// resumes from its last finished group and refitting traces nothing.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cluster/block_jobs.hpp"
#include "fit/fit_scene.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/walk/facets.hpp"

namespace smithlab::fitrun {

struct NdfData {
    FitFamily family;
    std::string label;                      // "ggx", "gtr(gamma=1.5)"
    std::vector<fit::DataPoint> training, validation, albedo;
    std::vector<double> validation_alphas;  // the geometric midpoints of training.alpha
    std::int64_t traced = 0, reused = 0;    // points
    std::int64_t walks_traced = 0;
};

// What tracing has done so far, for progress lines: points traced of points to trace.
using ProgressFn = std::function<void(std::int64_t done, std::int64_t total)>;

// The points of every NDF family of the scene, in its order. Checks every NDF (the registry's refusals name
// FILE:LINE: ndf.family) and builds each microsurface, then calls checked(), then reads the cache and traces what it
// lacks. Under MPI every rank calls it and traces (cluster/block_jobs.hpp); rank 0 reads and writes the cache and
// gets the data, the other ranks nothing. progress(points traced, points to trace).
// traffic: what rank 0 communicated, when given.
std::vector<NdfData> gather(const FitScene& scene, const NdfRegistry& registry, const std::filesystem::path& cache,
                            unsigned threads, const ProgressFn& progress, const std::function<void()>& checked = {},
                            cluster::Traffic* traffic = nullptr);

// A point to trace: its directions (the albedo estimator reads wi only) and its random stream.
struct TracePoint {
    Vec3 wi, wo;
    std::uint64_t stream;
};
enum class Estimator { eval, albedo };

// The points' split moments on one microsurface (fit/dataset.hpp: trace_eval_point, trace_albedo_point), in parallel
// (a point per block, merged in point order: the same bits for any --threads), point j from
// WalkRng(seed, points[j].stream, walk); done(k) once the first k points are merged.
std::vector<fit::SplitMoments> trace_points(const AnyNdf& ndf, const walk::Material& material,
                                            const std::vector<TracePoint>& points, Estimator estimator,
                                            std::uint64_t seed, std::int64_t walks, unsigned threads,
                                            const std::function<void(std::uint64_t)>& done);

// The NDF of a family at one alpha (alpha itself, or the parameter its registered roughness sets from alpha).
AnyNdf make_ndf(const NdfRegistry& registry, const FitFamily& family, double alpha);

}  // namespace smithlab::fitrun
