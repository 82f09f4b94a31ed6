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

struct Moments {
    double sum = 0.0, sum2 = 0.0;
    void add(double x) {
        sum += x;
        sum2 += x * x;
    }
    void merge(const Moments& o) {
        sum += o.sum;
        sum2 += o.sum2;
    }
};

/// The mean of n draws whose sums are m, and the standard error of that mean.
struct Estimate {
    double value, stderr_;
};
Estimate estimate(const Moments& m, std::int64_t n);

enum class Hemisphere { reflection, transmission, all };
enum class Component { specular, diffuse, all };
inline constexpr int all_orders = -1;  ///< an order selection: 0..3 for 1, 2, 3, 4+, or all

struct AlbedoTally {
    std::array<Moments, 2 * order_bins * 2> bins{};  ///< [hemisphere][order bin][component]
    std::int64_t walks = 0, events = 0, capped = 0;

    static std::size_t index(int hemisphere, int order, int component) {
        return (static_cast<std::size_t>(hemisphere) * order_bins + static_cast<std::size_t>(order)) * 2 +
            static_cast<std::size_t>(component);
    }
    void add(const WalkSample& s) {
        ++walks;
        events += s.order;
        capped += s.capped;
        if (s.weight == 0.0) return;
        bins[index(s.wo.z() > 0.0 ? 0 : 1, order_bin(s.order), s.diffuse() ? 1 : 0)].add(s.weight);
    }
    void merge(const AlbedoTally& o);
    /// The fraction of the incident energy leaving in the selection, with its standard error.
    Estimate albedo(Hemisphere h, int order, Component c) const;
};

/// f |cos theta_o| over equal-solid-angle bins: n_theta bands of equal width in cos theta_o per hemisphere (reflection
/// first, then transmission when asked), n_phi equal sectors of phi_o in [0, 2 pi), by order bin and component.
struct BrdfBins {
    int n_theta = 0, n_phi = 0;
    bool transmission = false;
    bool empty() const { return n_theta <= 0 || n_phi <= 0; }
};

struct BrdfTally {
    BrdfBins bins;
    std::vector<Moments> cells;  ///< [hemisphere][theta][phi][order bin][component]
    std::int64_t walks = 0;

    explicit BrdfTally(const BrdfBins& b);
    void add(const WalkSample& s);
    void merge(const BrdfTally& o);
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
    Moments total;
    std::int64_t walks = 0, events = 0, capped = 0;
    void add(const EvalSample& s);
    void merge(const EvalTally& o);
    Estimate value() const { return estimate(total, walks); }
    Estimate value(int order, Component c) const;
};

}  // namespace smithlab::walk
