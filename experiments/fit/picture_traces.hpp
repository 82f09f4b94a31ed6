// What the fit's pictures trace, per NDF family and alpha: the spheres (the scene's facets, and Lambertian ones), the
// directional albedos of Lambertian facets (the light single scattering misses) and the BRDF slices. Each trace is
// cached in OUT/cache/NDF/pictures/SET-A.csv as it finishes (fit/point_cache.hpp: keyed by all that defines it, every
// point's directions checked), so a second run of the same scene traces nothing and gives the same bits.
//
// The pictures' Philox streams: set << 56 | ndf << 44 | group << 32 | point. fit/data_sets.hpp's streams are
// set << 48 | ndf << 32 | group << 16 | point with set <= 2 and ndf < 2^16, all below 2^50; these have set >= 3 in
// bits 56.., so none collides with them, and a group may hold 2^32 points (a 1024-pixel sphere has 2^20 per light).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_data.hpp"
#include "fit/fit_scene.hpp"
#include "fit/picture_geometry.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fit {

// The light single scattering misses: directional albedos (the sample estimator) of Lambertian facets at these
// incidences, measured at these albedos.
inline constexpr double missing_theta[] = {0.0, 30.0, 60.0, 80.0};
inline constexpr double missing_albedos[] = {1.0, 0.75};
inline constexpr std::int64_t missing_walks = 100000;

// What defines the pictures' traces: the scene's [pictures], its facets and its seed.
struct PictureSpec {
    FitScene::Pictures pictures;
    std::string material;
    std::uint64_t seed;
    walk::EvalEstimator estimator;
};

// One NDF family's traced pictures, per alpha of the scene's lists.
struct PictureData {
    std::vector<std::vector<fit::SplitMoments>> spheres, lambert_spheres, lambert_albedo;  // per sphere_alpha
    std::vector<std::vector<fit::SplitMoments>> slices;                                    // per slice_alpha
};

// The traces of every NDF of data (in its order), read from the cache or traced on `threads` threads, with progress
// lines on stderr; walks_traced: the walks this run traced.
std::vector<PictureData> trace_pictures(const PictureSpec& spec, const std::vector<NdfData>& data,
                                        const SphereGroup& spheres, const std::vector<Pair>& slices,
                                        const NdfRegistry& registry, const std::filesystem::path& cache,
                                        unsigned threads, std::int64_t& walks_traced);

}  // namespace smithlab::fit
