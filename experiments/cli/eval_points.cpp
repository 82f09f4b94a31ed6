#include "cli/eval_points.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>

#include "cli/commands.hpp"
#include "scene/spaced.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

namespace {

constexpr long double degree = std::numbers::pi_v<long double> / 180.0L;

// N of a range: decimal digits only, in [2, max_axis_points].
std::int64_t parse_count(const std::string& text, const std::string& what) {
    const bool digits = !text.empty() && text.size() <= 9 && text.find_first_not_of("0123456789") == std::string::npos;
    const std::int64_t n = digits ? std::stoll(text) : -1;
    if (n < 2 || n > scene::max_axis_points)
        throw input_error(what + ": N must be an integer in [2, " + std::to_string(scene::max_axis_points) +
                          "] (one point: give it alone), got '" + text + "'");
    return n;
}

// The fields of "a:b:c..." split at each ':'.
std::vector<std::string> split_colons(const std::string& text) {
    std::vector<std::string> out(1);
    for (char ch : text) {
        if (ch == ':') out.emplace_back();
        else out.back() += ch;
    }
    return out;
}

}  // namespace

double mu_of_theta_deg(double theta, const std::string& what) {
    require(theta >= 0.0 && theta <= 180.0, what, "in [0, 180] degrees", theta);  // NaN too
    if (theta == 0.0) return INFINITY;
    if (theta == 90.0) return 0.0;
    if (theta == 180.0) return -INFINITY;
    // cot(theta) from the angle nearest the one where it is exact: 1 / tan(theta) near the normal, tan(90 - theta)
    // near grazing, -1 / tan(180 - theta) near the other pole, each difference exact (Sterbenz), so mu keeps its
    // relative accuracy everywhere. In long double, so that the angles with an exact cotangent give it (45 degrees:
    // mu = 1, where double's pi/4 gives 0.9999999999999999).
    long double t;
    if (theta < 45.0) t = 1.0L / std::tan(theta * degree);
    else if (theta <= 135.0) t = std::tan((90.0L - theta) * degree);
    else t = -1.0L / std::tan((180.0L - theta) * degree);
    return static_cast<double>(t);
}

std::vector<double> parse_range(const std::string& text, const std::string& what) {
    std::vector<std::string> f = split_colons(text);
    const bool log = f.size() == 4 && f[0] == "log";
    if (log) f.erase(f.begin());
    if (f.size() != 3) throw input_error(what + ": expected LO:HI:N or log:LO:HI:N, got '" + text + "'");
    const double lo = parse_number(f[0], what + " LO"), hi = parse_number(f[1], what + " HI");
    const std::int64_t n = parse_count(f[2], what);
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || (log && !(lo > 0.0)))
        throw input_error(what + ": LO and HI must be finite with LO < HI" + (log ? " and LO > 0 (log spacing)" : "") +
                          ", got '" + text + "'");
    return scene::spaced(lo, hi, n, log ? scene::Spacing::log : scene::Spacing::lin);
}

std::vector<EvalPoint> eval_points(const std::string& mu, const std::string& theta, const std::string& mu_range,
                                   const std::string& theta_range) {
    if (!mu.empty()) return {{std::nullopt, parse_number(mu, "--mu")}};
    if (!theta.empty()) {
        const double t = parse_number(theta, "--theta");
        return {{t, mu_of_theta_deg(t, "--theta")}};
    }
    std::vector<EvalPoint> out;
    if (!mu_range.empty())
        for (double m : parse_range(mu_range, "--mu-range")) out.push_back({std::nullopt, m});
    else
        for (double t : parse_range(theta_range, "--theta-range"))
            out.push_back({t, mu_of_theta_deg(t, "--theta-range")});
    return out;
}

}  // namespace smithlab::cli
