#include "smithlab/fit/dataset.hpp"

#include <charconv>
#include <cmath>

#include "smithlab/csv.hpp"

namespace smithlab::fit {

void SplitMoments::add(const Split& x) {
    ++walks;
    for (int k = 0; k < diffuse_bins; ++k) {
        if (x[k] == 0.0) continue;  // most walks fill one or two bins
        sum[k] += x[k];
        for (int l = k; l < diffuse_bins; ++l) cross[pair(k, l)] += x[k] * x[l];
    }
}

void SplitMoments::merge(const SplitMoments& o) {
    walks += o.walks;
    for (int k = 0; k < diffuse_bins; ++k) sum[k] += o.sum[k];
    for (int p = 0; p < pairs; ++p) cross[p] += o.cross[p];
    capped += o.capped;
}

namespace {

// The weights a^k of y(a) = sum_k a^k x_k (0 below min_k).
Split powers(const AlbedoPower& a) {
    Split w{};
    double p = 1.0;
    for (int k = 0; k < diffuse_bins; ++k, p *= a.albedo) w[k] = k >= a.min_k ? p : 0.0;
    return w;
}

}  // namespace

double covariance(const SplitMoments& m, const AlbedoPower& a, const AlbedoPower& b) {
    if (m.walks < 2) return 0.0;
    const Split wa = powers(a), wb = powers(b);
    const double n = static_cast<double>(m.walks);
    double s = 0.0;
    for (int k = 0; k < diffuse_bins; ++k)
        for (int l = 0; l < diffuse_bins; ++l) {
            const double xy = m.cross[k <= l ? SplitMoments::pair(k, l) : SplitMoments::pair(l, k)] / n;
            s += wa[k] * wb[l] * (xy - (m.sum[k] / n) * (m.sum[l] / n));
        }
    return s / (n - 1.0);  // the unbiased covariance of one walk's values, over n: that of the means
}

walk::Estimate at_albedo(const SplitMoments& m, const AlbedoPower& a) {
    if (m.walks <= 0) return {0.0, 0.0};
    const Split w = powers(a);
    double y = 0.0;
    for (int k = 0; k < diffuse_bins; ++k) y += w[k] * m.sum[k];
    return {y / static_cast<double>(m.walks), std::sqrt(std::max(0.0, covariance(m, a, a)))};
}

double tail_bound(const SplitMoments& m, const AlbedoPower& a) {
    if (m.walks <= 0 || a.albedo == 1.0) return 0.0;
    return std::pow(a.albedo, diffuse_bins - 1) * m.sum[diffuse_bins - 1] / static_cast<double>(m.walks);
}

Vec3 Directions::wi() const { return direction_from_deg(theta_i, 0.0); }
Vec3 Directions::wo() const { return direction_from_deg(theta_o, phi); }

namespace {
std::string indexed(std::string name, int k) {
    name += std::to_string(k);
    return name;
}
}  // namespace

std::vector<std::string> moment_columns() {
    std::vector<std::string> c{"walks"};
    for (int k = 0; k < diffuse_bins; ++k) c.push_back(indexed("s", k));
    for (int k = 0; k < diffuse_bins; ++k)
        for (int l = k; l < diffuse_bins; ++l) c.push_back(indexed(indexed("q", k) + "_", l));
    return c;
}

std::vector<std::string> moment_fields(const SplitMoments& m) {
    std::vector<std::string> f{std::to_string(m.walks)};
    for (double s : m.sum) f.push_back(format_g17(s));
    for (double q : m.cross) f.push_back(format_g17(q));
    return f;
}

bool read_moment_fields(const std::vector<std::string>& fields, std::size_t first, SplitMoments& m) {
    if (fields.size() < first + 1 + diffuse_bins + SplitMoments::pairs) return false;
    auto number = [](const std::string& s, auto& out) {
        const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
        return r.ec == std::errc{} && r.ptr == s.data() + s.size();
    };
    std::size_t i = first;
    if (!number(fields[i++], m.walks) || m.walks < 0) return false;
    for (double& s : m.sum)
        if (!number(fields[i++], s) || !std::isfinite(s)) return false;
    for (double& q : m.cross)
        if (!number(fields[i++], q) || !std::isfinite(q)) return false;
    return true;
}

}  // namespace smithlab::fit
