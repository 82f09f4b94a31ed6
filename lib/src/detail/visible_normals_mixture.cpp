#include "smithlab/detail/visible_normals_mixture.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

namespace smithlab::detail {

namespace {

constexpr int dictionary = 49;   // alpha = r0 2^(j/2), j = -24..24
constexpr int grid = 256;        // points in x for the fit
constexpr int per_bin = 64;      // points in x per bin for the squeeze
constexpr double far_s = 1e15;   // the tail is checked out to far_s r0^2
constexpr double margin = 0.25;  // of a bin's range, on each side
// A lobe costs a root and a few products per draw, a try a GGX visible normal and the squeeze (~15x more): a lobe is
// kept when dropping it would raise K, the tries per normal, by more than this.
constexpr double lobe_cost = 0.05;

double ggx_P22(double a2, double s) {
    const double d = a2 + s;
    return a2 / (std::numbers::pi * d * d);
}

// The points of the fit: x in (0, 1) midpoints, s = r0^2 x / (1 - x), with the D cos mass P22(s) ds of each.
struct FitGrid {
    std::vector<double> s, P22, mass;
};

FitGrid fit_grid(const std::function<double(double)>& P22, double r02) {
    FitGrid f;
    for (int i = 0; i < grid; ++i) {
        const double x = (i + 0.5) / grid, s = r02 * x / (1.0 - x), p = P22(s);
        f.s.push_back(s);
        f.P22.push_back(p);
        f.mass.push_back(p * r02 / ((1.0 - x) * (1.0 - x)));
    }
    return f;
}

double mixture(const std::vector<double>& a2, const std::vector<double>& w, double s) {
    double q = 0.0;
    for (std::size_t k = 0; k < a2.size(); ++k) q += w[k] * ggx_P22(a2[k], s);
    return q;
}

// Expectation-maximization of the weights of fixed lobes on the grid's mass (the likelihood of the D cos law of s).
void em(const FitGrid& f, const std::vector<double>& a2, std::vector<double>& w, int iterations) {
    for (int it = 0; it < iterations; ++it) {
        std::vector<double> next(w.size(), 0.0);
        double total = 0.0;
        for (std::size_t i = 0; i < f.s.size(); ++i) {
            const double q = mixture(a2, w, f.s[i]);
            if (!(q > 0.0) || !(f.mass[i] > 0.0)) continue;
            for (std::size_t k = 0; k < w.size(); ++k) next[k] += f.mass[i] * w[k] * ggx_P22(a2[k], f.s[i]) / q;
            total += f.mass[i];
        }
        if (!(total > 0.0)) return;
        for (std::size_t k = 0; k < w.size(); ++k) w[k] = next[k] / total;
    }
}

// The greatest P22 / Q on the grid and the tail points.
double grid_bound(const FitGrid& f, const std::vector<double>& tail_s, const std::vector<double>& tail_P22,
                  const std::vector<double>& a2, const std::vector<double>& w) {
    const double sum = std::accumulate(w.begin(), w.end(), 0.0);
    double K = 0.0;
    for (std::size_t i = 0; i < f.s.size(); ++i) K = std::max(K, f.P22[i] * sum / mixture(a2, w, f.s[i]));
    for (std::size_t i = 0; i < tail_s.size(); ++i) K = std::max(K, tail_P22[i] * sum / mixture(a2, w, tail_s[i]));
    return K;
}

// Moves the weights and the lobes' alpha^2 (multiplicative steps, coordinate by coordinate) while the bound
// decreases; then drops the lightest lobes while that raises the bound by less than lobe_cost. Returns the bound.
double lower_bound(const FitGrid& f, const std::vector<double>& tail_s, const std::vector<double>& tail_P22,
                   std::vector<double>& a2, std::vector<double>& w) {
    auto descend = [&](std::vector<double>& a2_, std::vector<double>& w_) {
        double K = grid_bound(f, tail_s, tail_P22, a2_, w_);
        for (double step : {1.5, 1.1, 1.02})
            for (bool moved = true; moved;) {
                moved = false;
                for (std::vector<double>* p : {&w_, &a2_})
                    for (std::size_t k = 0; k < w_.size(); ++k)
                        for (double factor : {step, 1.0 / step}) {
                            const double keep = (*p)[k];
                            (*p)[k] = keep * factor;
                            const double Kt = grid_bound(f, tail_s, tail_P22, a2_, w_);
                            if (Kt < K * (1.0 - 1e-9)) K = Kt, moved = true;
                            else (*p)[k] = keep;
                        }
            }
        return K;
    };
    double K = descend(a2, w);
    while (w.size() > 1) {
        const std::size_t k = std::min_element(w.begin(), w.end()) - w.begin();
        std::vector<double> a2_less = a2, w_less = w;
        a2_less.erase(a2_less.begin() + k), w_less.erase(w_less.begin() + k);
        const double K_less = descend(a2_less, w_less);
        if (!(K_less < K + lobe_cost)) break;
        a2 = std::move(a2_less), w = std::move(w_less), K = K_less;
    }
    const double sum = std::accumulate(w.begin(), w.end(), 0.0);
    for (double& x : w) x /= sum;
    return K;
}

}  // namespace

std::optional<GgxMixture> GgxMixture::fit(const std::function<double(double)>& P22, double r0) {
    const double r02 = r0 * r0;
    if (!(r02 > 1e-250 && r02 < 1e250)) return std::nullopt;  // the grid's s, s^2 and the tail's 1e15 r0^2 in range
    const FitGrid f = fit_grid(P22, r02);
    std::vector<double> tail_s, tail_P22;
    for (double t = 1e4; t <= far_s; t *= 10.0) tail_s.push_back(t * r02), tail_P22.push_back(P22(t * r02));
    for (double p : f.P22)
        if (!(p >= 0.0 && p < INFINITY)) return std::nullopt;

    std::vector<double> a2(dictionary), w(dictionary, 1.0 / dictionary);
    for (int j = 0; j < dictionary; ++j) a2[j] = r02 * std::exp2(j - (dictionary - 1) / 2);  // alpha^2 = r0^2 2^j'
    em(f, a2, w, 60);
    std::vector<int> order(dictionary);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int i, int j) { return w[i] > w[j]; });
    std::vector<double> ka2, kw;
    for (int i = 0; i < max_lobes; ++i) ka2.push_back(a2[order[i]]), kw.push_back(w[order[i]]);
    em(f, ka2, kw, 30);
    if (!(lower_bound(f, tail_s, tail_P22, ka2, kw) <= max_bound)) return std::nullopt;

    GgxMixture m;
    m.r02_ = r02;
    for (std::size_t k = 0; k < ka2.size(); ++k) {
        if (!(kw[k] > 1e-12)) continue;
        m.alpha2_[m.lobes_] = ka2[k];
        m.alpha_[m.lobes_] = std::sqrt(ka2[k]);
        m.weight_[m.lobes_] = kw[k];
        ++m.lobes_;
    }
    // The squeeze: per bin of x, the least and greatest rho over per_bin + 1 points (the ends included), widened.
    double K = 0.0;
    for (int b = 0; b < bins; ++b) {
        double lo = INFINITY, hi = 0.0;
        for (int j = 0; j <= per_bin; ++j) {
            const double x = (b + static_cast<double>(j) / per_bin) / bins;
            if (!(x < 1.0)) break;
            const double s = r02 * x / (1.0 - x), rho = P22(s) / m.Q(s);
            if (!(rho >= 0.0 && rho < INFINITY)) return std::nullopt;
            lo = std::min(lo, rho), hi = std::max(hi, rho);
        }
        if (b == bins - 1)
            for (double s : tail_s) {
                const double rho = P22(s) / m.Q(s);
                if (!(rho >= 0.0 && rho < INFINITY)) return std::nullopt;
                lo = std::min(lo, rho), hi = std::max(hi, rho);
            }
        const double pad = margin * (hi - lo) + 1e-12 * hi;
        m.lo_[b] = std::max(0.0, lo - pad);
        m.hi_[b] = hi + pad;
        K = std::max(K, m.hi_[b]);
    }
    // A tail heavier than the lobes' r^-4: rho still growing at the far end has no bound.
    const double r_far = P22(tail_s.back()) / m.Q(tail_s.back()),
                 r_before = P22(tail_s[tail_s.size() - 2]) / m.Q(tail_s[tail_s.size() - 2]);
    if (r_far > r_before * (1.0 + 1e-6) || !(K > 0.0) || K > max_bound) return std::nullopt;
    m.K_ = K;
    return m;
}

}  // namespace smithlab::detail
