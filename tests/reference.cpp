// tests/reference.cpp -- the bodies of tests/reference.hpp (the 50-digit references), compiled once.
#include "reference.hpp"

#include <stdexcept>

namespace ref {

real pi() { return boost::math::constants::pi<real>(); }

real gtr_c(double alpha_d, double gamma_d) {
    const real a(alpha_d), g(gamma_d);
    if (alpha_d == 1.0) return 1 / pi();
    if (gamma_d == 1.0) return (a * a - 1) / (pi() * log(a * a));
    return (g - 1) * (a * a - 1) / (pi() * (1 - pow(a * a, 1 - g)));
}
real gtr_D(double alpha_d, double gamma_d, double cos_d) {
    const real a(alpha_d), g(gamma_d), c(cos_d);
    return gtr_c(alpha_d, gamma_d) / pow(1 + (a * a - 1) * c * c, g);
}
SlopeDensity gtr(double alpha_d, double gamma_d) {
    const real a(alpha_d), g(gamma_d), c = gtr_c(alpha_d, gamma_d);
    return [=](const real& r2) { return c * pow(r2 + 1, g - 2) / pow(r2 + a * a, g); };
}
SlopeDensity ggx(double alpha_d) {
    const real a(alpha_d);
    return [=](const real& r2) { return a * a / (pi() * (r2 + a * a) * (r2 + a * a)); };
}
SlopeDensity beckmann(double alpha_d) {
    const real a(alpha_d);
    return [=](const real& r2) { return exp(-r2 / (a * a)) / (pi() * a * a); };
}
SlopeDensity blinn(double n_d) {
    const real n(n_d);
    return [=](const real& r2) { return (n + 2) / (2 * pi()) * pow(1 + r2, -(n + 4) / 2); };
}

real Lambda(const SlopeDensity& f, double mu_d) {
    const real mu(mu_d);
    auto g = [&](const real& r) {
        const real d = r * r - mu * mu;
        // Beyond r = 1e60 (1 + mu) every density here has fallen at least as r^-4, so the rest of the integral is
        // below 1e-60 of it; cutting there keeps pow() from overflowing even the 50-digit exponent range.
        if (d <= 0 || r > real("1e60") * (1 + mu)) return real(0);
        const real fr = f(r * r);
        return fr == 0 ? fr : fr * r * (sqrt(d) - mu * acos(mu / r));
    };
    const real tol("1e-24");
    // The rules live across calls (one pair per thread): Boost computes their abscissas and weights level by level
    // on first need, at 50 digits, which was 60% of a call when each call built its own. The nodes are the same
    // whenever they are computed, and so is every result, bit for bit (compared on 540 points of the tests' grids).
    thread_local boost::math::quadrature::tanh_sinh<real> ts(12);
    thread_local boost::math::quadrature::exp_sinh<real> es(12);
    const real I = ts.integrate(g, mu, 2 * mu, tol) + es.integrate(g, 2 * mu, real(INFINITY), tol);
    return 2 * I / mu;
}

real Lambda_dimov(int gamma, double alpha_d, double mu_d) {
    using wide = boost::multiprecision::cpp_bin_float_100;
    const wide a(alpha_d), mu(mu_d), A = sqrt(mu * mu + a * a), B = sqrt(mu * mu + 1);
    const wide a2 = a * a, a4 = a2 * a2, a6 = a4 * a2, a8 = a4 * a4;
    switch (gamma) {
        case 0: return real((B - mu) / (2 * mu));
        case 1: return real((A - B + mu * boost::multiprecision::asinh(mu) - mu * log(mu + A)) / (mu * log(a2)));
        case 2: return real((A - mu) / (2 * mu));
        case 3:
            return real((3 * a4 + 2 * mu * (mu - A) + a2 * (1 + 2 * mu * (mu - A))) / (4 * (1 + a2) * mu * A));
        case 4: {
            const wide den = 16 * (a4 + a2 + 1) * mu * pow(mu * mu + a2, wide(1.5));
            return real((15 * a8 + 3 * a4 + 8 * mu * mu * mu * (mu - A) + a6 * (6 + 24 * mu * mu - 8 * mu * A)) / den +
                        4 * a2 * mu * (-2 * A + mu * (3 + 2 * mu * (mu - A))) * (a2 + 1) / den);
        }
    }
    throw std::invalid_argument("gamma");
}

real Lambda_beckmann(double alpha_d, double mu_d) {
    const real a = real(mu_d) / real(alpha_d);
    return (exp(-a * a) / (a * sqrt(pi())) - boost::math::erfc(a)) / 2;
}

double rel_err(double x, const real& ref) {
    return static_cast<double>(boost::multiprecision::abs((real(x) - ref) / ref));
}

bool close(double got, const real& want, double tol) {
    if (!std::isfinite(got)) return false;
    if (want < std::numeric_limits<double>::min()) return got >= 0.0 && got < 2 * std::numeric_limits<double>::min();
    return rel_err(got, want) <= tol;
}

}  // namespace ref
