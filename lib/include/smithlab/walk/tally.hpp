/// @file
/// smithlab/walk/tally.hpp -- what a cell of walks keeps: sums and sums of squares of the energy leaving, by
/// hemisphere, scattering order (1, 2, 3, 4+) and component (specular: every event a facet reflection; diffuse: any
/// diffuse event), and, only when asked, by outgoing direction. Each walk puts its weight in exactly one bin, so the
/// sums of squares of a union of bins are the sums of its bins', and every aggregate's standard error is exact.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "smithlab/walk/walk.hpp"

namespace smithlab::walk {

/// The sum and the sum of squares of a tally's draws.
struct Moments {
    /// The sum of the draws, and of their squares.
    /// @{
    double sum = 0.0, sum2 = 0.0;
    /// @}
    /// Adds one draw x.
    void add(double x) {
        sum += x;
        sum2 += x * x;
    }
    /// Adds the draws of o.
    void merge(const Moments& o) {
        sum += o.sum;
        sum2 += o.sum2;
    }
};

/// The mean of n draws whose sums are m, and the standard error of that mean.
struct Estimate {
    /// The mean, and its standard error.
    /// @{
    double value, stderr_;
    /// @}
};
/// The mean of n draws with the sums m, and its standard error sqrt((sum2 / n - mean^2) / (n - 1)) (0 for n = 1; both 0
/// for n = 0).
Estimate estimate(const Moments& m, std::int64_t n);

/// The hemisphere of a selection: reflection (wo.z > 0), transmission (wo.z < 0), or both.
enum class Hemisphere { reflection, transmission, all };
/// The component of a selection: specular (every event a facet reflection), diffuse (any diffuse event), or both.
enum class Component { specular, diffuse, all };
inline constexpr int all_orders = -1;  ///< an order selection: 0..3 for 1, 2, 3, 4+, or all

/// The sample estimator's tallies of a cell: the energy leaving by hemisphere, order bin and component.
struct AlbedoTally {
    std::array<Moments, 2 * order_bins * 2> bins{};  ///< [hemisphere][order bin][component]
    /// The walks, their hits in all, and the walks capped (WalkSample::capped).
    /// @{
    std::int64_t walks = 0, events = 0, capped = 0;
    /// @}

    /// The index in `bins` of (hemisphere 0 or 1, order bin, component 0 specular or 1 diffuse).
    static std::size_t index(int hemisphere, int order, int component) {
        return (static_cast<std::size_t>(hemisphere) * order_bins + static_cast<std::size_t>(order)) * 2 +
            static_cast<std::size_t>(component);
    }
    /// Adds one walk: its weight to the bin of its exit.
    void add(const WalkSample& s) {
        ++walks;
        events += s.order;
        capped += s.capped;
        if (s.weight == 0.0) return;
        bins[index(s.wo.z() > 0.0 ? 0 : 1, order_bin(s.order), s.diffuse() ? 1 : 0)].add(s.weight);
    }
    /// Adds the walks of o.
    void merge(const AlbedoTally& o);
    /// The fraction of the incident energy leaving in the selection, with its standard error.
    Estimate albedo(Hemisphere h, int order, Component c) const;
};

/// f |cos theta_o| over equal-solid-angle bins: n_theta bands of equal width in cos theta_o per hemisphere (reflection
/// first, then transmission when asked), n_phi equal sectors of phi_o in [0, 2 pi), by order bin and component.
struct BrdfBins {
    /// The bands in cos theta_o per hemisphere, and the sectors in phi_o.
    /// @{
    int n_theta = 0, n_phi = 0;
    /// @}
    /// Whether the transmission hemisphere is tallied too.
    bool transmission = false;
    /// Whether no directional tally is asked for.
    bool empty() const { return n_theta <= 0 || n_phi <= 0; }
};

/// The sample estimator's directional tallies of a cell: the energy leaving by bin of BrdfBins, order bin and
/// component.
struct BrdfTally {
    /// The bins.
    BrdfBins bins;
    std::vector<Moments> cells;  ///< [hemisphere][theta][phi][order bin][component]
    /// The walks.
    std::int64_t walks = 0;

    /// Every bin of b, empty.
    explicit BrdfTally(const BrdfBins& b);
    /// Adds one walk: its weight to the bin of its exit direction.
    void add(const WalkSample& s);
    /// Adds the walks of o (same bins).
    void merge(const BrdfTally& o);
    /// The index in `cells` of a bin's order bin and component (0 specular, 1 diffuse).
    std::size_t index(int hemisphere, int theta, int phi, int order, int component) const;
    /// The mean of f |cos theta_o| over the bin (its energy over its solid angle), with its standard error.
    Estimate value(int hemisphere, int theta, int phi, int order, Component c) const;
    double solid_angle() const;  ///< of one bin
};

/// The eval estimator's tallies: f |cos theta_o| by order bin and component, over n walks. A walk adds to several
/// bins, so each selection offered keeps its own sums (their variances do not add).
struct EvalTally {
    std::array<Moments, order_bins * 2> bins{};  ///< [order bin][component]
    std::array<Moments, order_bins> orders{};    ///< [order bin], both components
    /// Every bin and component at once: the estimate of f |cos theta_o|.
    Moments total;
    /// The walks, their hits in all, and the walks capped (EvalSample::capped).
    /// @{
    std::int64_t walks = 0, events = 0, capped = 0;
    /// @}
    /// Adds one walk's estimate to every selection.
    void add(const EvalSample& s);
    /// Adds the walks of o.
    void merge(const EvalTally& o);
    /// f(wi, wo) |cos theta_o| over every order and component, with its standard error.
    Estimate value() const { return estimate(total, walks); }
    /// The same for one order bin (or all_orders) and component.
    Estimate value(int order, Component c) const;
};

}  // namespace smithlab::walk
