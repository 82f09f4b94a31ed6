/// @file
/// smithlab/fit/dataset.hpp -- what the diffuse fitter fits: path-traced values split by the number of diffuse events.
///
/// A walk on facets whose diffuse events each multiply by the albedo (lambert, fresnel-diffuse) and that depend on it
/// nowhere else, traced at albedo 1 and tallied by the number k of diffuse events (walk.hpp, diffuse_bins), gives the
/// result at any albedo a as
///     y(a) = sum_k a^k y_k,
/// one trace for every albedo. SplitMoments keeps, per walk, the vector x_k and its sums and sums of products, so the
/// standard error of y(a), and the covariance of y(a) and y(b) (the same walks), are exact. The last bin holds
/// k >= diffuse_bins - 1; it is weighted a^(diffuse_bins - 1), which is exact at a = 1 and 0 and overestimates by at
/// most that bin's value otherwise (tail_bound).
///
/// A point is one eval-estimator value f(wi, wo) |cos theta_o| (walk.hpp, eval_walk) or one directional albedo (the
/// sample estimator, reflection), on one microsurface.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "smithlab/geometry.hpp"
#include "smithlab/util/parallel.hpp"
#include "smithlab/walk/tally.hpp"
#include "smithlab/walk/walk.hpp"

namespace smithlab::fit {

using walk::diffuse_bins;
/// One walk's value split by its diffuse events k: x_k in bin diffuse_bin(k) (walk.hpp), so that sum_k a^k x_k is its
/// value at albedo a.
using Split = std::array<double, diffuse_bins>;

/// The moments of a point's split values over its walks: the sums of x_k and of x_k x_l, from which the mean and the
/// variance at every albedo follow exactly.
struct SplitMoments {
    /// The number of products x_k x_l with k <= l.
    static constexpr int pairs = diffuse_bins * (diffuse_bins + 1) / 2;
    /// The walks.
    std::int64_t walks = 0;
    /// The sum of x_k over the walks, per bin.
    Split sum{};
    std::array<double, pairs> cross{};  ///< sum of x_k x_l, k <= l, row by row
    std::int64_t capped = 0;            ///< walks cut short (walk.hpp), counted when traced (the cache keeps no count)

    /// The index in `cross` of x_k x_l, k <= l.
    static int pair(int k, int l) {  // k <= l
        return k * diffuse_bins - k * (k - 1) / 2 + (l - k);
    }
    /// Adds one walk's split value x.
    void add(const Split& x);
    /// Adds the walks of o.
    void merge(const SplitMoments& o);
};

/// Which diffuse events a value counts: k >= min_k (1: the diffuse part; 0: everything).
struct AlbedoPower {
    /// The albedo a.
    double albedo;
    /// The fewest diffuse events counted.
    int min_k = 1;
};

/// The mean of y(a) = sum_{k >= min_k} a^k x_k over the walks, with its standard error.
walk::Estimate at_albedo(const SplitMoments& m, const AlbedoPower& a);
/// The covariance of the means of y(a) and y(b) (the same walks).
double covariance(const SplitMoments& m, const AlbedoPower& a, const AlbedoPower& b);
/// An upper bound on what the last bin's weighting a^(diffuse_bins - 1) adds at albedo a (0 at a = 1).
double tail_bound(const SplitMoments& m, const AlbedoPower& a);

/// The geometry of a point: degrees; phi the azimuth of wo from wi's plane.
struct Directions {
    /// The incidence and exit angles from the normal, and the azimuth of wo from wi's plane, in degrees.
    /// @{
    double theta_i, theta_o, phi;
    /// @}
    /// The unit directions of theta_i (in the xz-plane) and of (theta_o, phi).
    /// @{
    Vec3 wi() const;
    Vec3 wo() const;
    /// @}
};

/// One traced point: a surface (its roughness alpha: the NDF family and the material are the dataset's), a pair of
/// directions (eval) or one (albedo: theta_o, phi unused), and its moments.
struct DataPoint {
    /// The surface's roughness.
    double alpha;
    /// Its directions.
    Directions dir;
    /// Its moments.
    SplitMoments moments;
};

/// The estimator of the fitter's eval points: the lowest equal-error time at every point bench_fit measures (walk.hpp).
inline constexpr walk::EvalEstimator fit_estimator = walk::EvalEstimator::reciprocal;

/// The eval-estimator point: f(wi, wo) |cos theta_o| split by diffuse events over `walks` walks drawn from
/// WalkRng(seed, cell, k), one thread (the caller runs points in parallel), by the estimator with the lowest
/// equal-error time (fit_estimator) unless told another.
template <class Microsurface, class M>
SplitMoments trace_eval_point(const Microsurface& ms, const M& material, const Vec3& wi, const Vec3& wo,
                              std::uint64_t seed, std::uint64_t cell, std::int64_t walks,
                              walk::EvalEstimator estimator = fit_estimator) {
    SplitMoments m;
    for (std::int64_t k = 0; k < walks; ++k) {
        WalkRng g(seed, cell, static_cast<std::uint64_t>(k));
        const walk::EvalSample e = walk::eval_walk(ms, material, wi, wo, g, {}, estimator);
        m.add(e.by_diffuse);
        m.capped += e.capped;
    }
    return m;
}

/// The directional albedo (the energy leaving into the upper hemisphere) split by diffuse events: the sample estimator.
template <class Microsurface, class M>
SplitMoments trace_albedo_point(const Microsurface& ms, const M& material, const Vec3& wi, std::uint64_t seed,
                                std::uint64_t cell, std::int64_t walks) {
    SplitMoments m;
    for (std::int64_t k = 0; k < walks; ++k) {
        WalkRng g(seed, cell, static_cast<std::uint64_t>(k));
        const walk::WalkSample s = walk::sample_walk(ms, material, wi, g);
        Split x{};
        if (s.escaped && s.wo.z() > 0.0) x[walk::diffuse_bin(s.diffuse_events)] = s.weight;
        m.add(x);
        m.capped += s.capped;
    }
    return m;
}

/// SplitMoments as CSV fields (walks, the sums, the products; 17 significant digits: read back bit for bit) and back.
std::vector<std::string> moment_fields(const SplitMoments& m);
/// Reads what moment_fields wrote from fields[first..]; false when there are too few fields or one is not a number.
bool read_moment_fields(const std::vector<std::string>& fields, std::size_t first, SplitMoments& m);
/// The header names of moment_fields' columns.
std::vector<std::string> moment_columns();

}  // namespace smithlab::fit
