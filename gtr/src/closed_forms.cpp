#include "smithlab/gtr/closed_forms.hpp"

#include <boost/math/special_functions/log1p.hpp>
#include <cmath>
#include <string>

#include "smithlab/errors.hpp"

namespace smithlab {

bool gtr_has_closed_form(double gamma) { return gamma >= 0.0 && gamma <= 4.0 && gamma == std::floor(gamma); }

namespace {

double lambda0(double mu) { return 1.0 / (2.0 * mu * (mu + std::hypot(mu, 1.0))); }

double lambda1(double alpha, double mu) {
    const double A = std::hypot(mu, alpha), B = std::hypot(mu, 1.0);
    const double one_minus_a2 = (1.0 - alpha) * (1.0 + alpha);
    // h = (1 - alpha^2) / (-2 ln alpha) -> 1 as alpha -> 1 (uniform D, where gamma = 1 meets gamma = 0).
    const double h = alpha == 1.0 ? 1.0 : one_minus_a2 / (-2.0 * std::log(alpha));
    const double x = one_minus_a2 / ((A + B) * (mu + A));  // (mu + B)/(mu + A) - 1
    // log1pmx(x) = log1p(x) - x ~ -x^2/2: no cancellation, and log1pmx(x)/x -> 0 as x -> 0.
    const double lx = x == 0.0 ? 0.0 : boost::math::log1pmx(x) / x;
    return h / ((A + B) * (mu + A)) * (A / mu - lx);
}

double lambda2(double alpha, double mu) { return alpha * alpha / (mu + std::hypot(mu, alpha)) / (2.0 * mu); }

double lambda3(double alpha, double mu) {
    const double a2 = alpha * alpha, A = std::hypot(mu, alpha);
    const double w = a2 / (mu + A);
    return w * w / (1.0 + a2) * ((mu + A) / A + (1.0 + 3.0 * a2) / (4.0 * mu * A));
}

double lambda4(double alpha, double mu) {
    const double a2 = alpha * alpha, a4 = a2 * a2, A = std::hypot(mu, alpha);
    const double s = mu + A, v = a2 / A, p = mu / s;
    const double c = a4 + a2 + 1.0;
    const double tail = (3.0 * A + mu + 2.0 * a2 * (3.0 * A + 5.0 * mu) + a4 * (15.0 * A + 37.0 * mu)) / (mu * s * s * s);
    const double bracket = 48.0 * mu * p * p + 12.0 * p * p / mu * (1.0 + a2 * (5.0 * A + 7.0 * mu) / s) + tail;
    return v * v * v / (16.0 * c) * bracket;
}

}  // namespace

double Lambda_gtr_closed(double alpha, int gamma, double mu) {
    switch (gamma) {
        case 0: return lambda0(mu);
        case 1: return lambda1(alpha, mu);
        case 2: return lambda2(alpha, mu);
        case 3: return lambda3(alpha, mu);
        case 4: return lambda4(alpha, mu);
        default: throw input_error("gtr: no closed-form Lambda for gamma = " + std::to_string(gamma) + " (only 0..4)");
    }
}

}  // namespace smithlab
