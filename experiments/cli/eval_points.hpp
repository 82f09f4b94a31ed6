// The directions `smithlab eval` evaluates: one mu = cot(theta_v) (--mu), one angle theta_v in degrees (--theta),
// or a range of either (--mu-range, --theta-range), spaced as a scene's axes are (scene/strict_table.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace smithlab::cli {

struct EvalPoint {
    std::optional<double> theta;  // degrees, where the point was given as an angle
    double mu;                    // cot(theta)
};

// mu = cot(theta) for theta in [0, 180] degrees from the normal: 0 gives +inf (normal), 90 gives 0 (grazing), above
// 90 a direction below the surface (mu < 0), 180 gives -inf. Outside [0, 180] or NaN: an input_error naming `what`.
double mu_of_theta_deg(double theta, const std::string& what);

// "LO:HI:N" (N points evenly spaced, LO and HI included) or "log:LO:HI:N" (evenly spaced in log, LO > 0): LO < HI
// finite, 2 <= N <= 1e7, the rule of a scene's {lin = [lo, hi], n = N} and {log = [lo, hi], n = N}. A malformed text,
// NaN or a value out of these bounds is an input_error naming `what`.
std::vector<double> parse_range(const std::string& text, const std::string& what);

// The points of the one option given (its text non-empty); the angles checked against [0, 180].
std::vector<EvalPoint> eval_points(const std::string& mu, const std::string& theta, const std::string& mu_range,
                                   const std::string& theta_range);

}  // namespace smithlab::cli
