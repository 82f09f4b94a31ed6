#include "smithlab/walk/tally.hpp"

#include <numbers>

namespace smithlab::walk {

Estimate estimate(const Moments& m, std::int64_t n) {
    if (n <= 0) return {0.0, 0.0};
    const double N = static_cast<double>(n), mean = m.sum / N;
    if (n == 1) return {mean, 0.0};
    const double var = std::max(0.0, (m.sum2 / N - mean * mean) * N / (N - 1.0));
    return {mean, std::sqrt(var / N)};
}

void AlbedoTally::merge(const AlbedoTally& o) {
    for (std::size_t i = 0; i < bins.size(); ++i) bins[i].merge(o.bins[i]);
    walks += o.walks;
    events += o.events;
    capped += o.capped;
}

Estimate AlbedoTally::albedo(Hemisphere h, int order, Component c) const {
    Moments m;
    for (int hi = 0; hi < 2; ++hi) {
        if (h != Hemisphere::all && static_cast<int>(h) != hi) continue;
        for (int o = 0; o < order_bins; ++o) {
            if (order != all_orders && order != o) continue;
            for (int ci = 0; ci < 2; ++ci)
                if (c == Component::all || static_cast<int>(c) == ci) m.merge(bins[index(hi, o, ci)]);
        }
    }
    return estimate(m, walks);
}

BrdfTally::BrdfTally(const BrdfBins& b)
    : bins(b), cells(static_cast<std::size_t>((b.transmission ? 2 : 1) * b.n_theta * b.n_phi * order_bins * 2)) {}

std::size_t BrdfTally::index(int hemisphere, int theta, int phi, int order, int component) const {
    return (((static_cast<std::size_t>(hemisphere) * bins.n_theta + theta) * bins.n_phi + phi) * order_bins + order) *
        2 +
        component;
}

void BrdfTally::add(const WalkSample& s) {
    ++walks;
    if (s.weight == 0.0) return;
    const int hemi = s.wo.z() > 0.0 ? 0 : 1;
    if (hemi == 1 && !bins.transmission) return;
    // Equal bands of |cos theta_o| from the pole: band 0 holds the directions nearest the normal.
    const double c = std::abs(s.wo.z());
    const int t = std::clamp(static_cast<int>((1.0 - c) * bins.n_theta), 0, bins.n_theta - 1);
    double phi = std::atan2(s.wo.y(), s.wo.x());
    if (phi < 0.0) phi += 2.0 * std::numbers::pi;
    const int p = std::clamp(static_cast<int>(phi / (2.0 * std::numbers::pi) * bins.n_phi), 0, bins.n_phi - 1);
    cells[index(hemi, t, p, order_bin(s.order), s.diffuse() ? 1 : 0)].add(s.weight);
}

void BrdfTally::merge(const BrdfTally& o) {
    for (std::size_t i = 0; i < cells.size(); ++i) cells[i].merge(o.cells[i]);
    walks += o.walks;
}

double BrdfTally::solid_angle() const { return 2.0 * std::numbers::pi / (bins.n_theta * bins.n_phi); }

Estimate BrdfTally::value(int hemisphere, int theta, int phi, int order, Component c) const {
    Moments m;
    for (int o = 0; o < order_bins; ++o) {
        if (order != all_orders && order != o) continue;
        for (int ci = 0; ci < 2; ++ci)
            if (c == Component::all || static_cast<int>(c) == ci) m.merge(cells[index(hemisphere, theta, phi, o, ci)]);
    }
    const Estimate e = estimate(m, walks);
    const double w = solid_angle();
    return {e.value / w, e.stderr_ / w};
}

void EvalTally::add(const EvalSample& s) {
    ++walks;
    events += s.events;
    capped += s.capped;
    double t = 0.0;
    for (int o = 0; o < order_bins; ++o) {
        bins[o * 2].add(s.specular[o]);
        bins[o * 2 + 1].add(s.diffuse[o]);
        orders[o].add(s.specular[o] + s.diffuse[o]);
        t += s.specular[o] + s.diffuse[o];
    }
    total.add(t);
}

void EvalTally::merge(const EvalTally& o) {
    for (std::size_t i = 0; i < bins.size(); ++i) bins[i].merge(o.bins[i]);
    for (std::size_t i = 0; i < orders.size(); ++i) orders[i].merge(o.orders[i]);
    total.merge(o.total);
    walks += o.walks;
    events += o.events;
    capped += o.capped;
}

Estimate EvalTally::value(int order, Component c) const {
    if (c == Component::all) return estimate(orders[order], walks);
    return estimate(bins[order * 2 + (c == Component::diffuse ? 1 : 0)], walks);
}

}  // namespace smithlab::walk
