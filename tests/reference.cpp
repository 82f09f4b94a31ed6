// tests/reference.cpp -- the bodies of tests/reference.hpp (the 50-digit references), compiled once.
#include "reference.hpp"

#include <boost/math/special_functions/gamma.hpp>
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

SlopeDensity student_t(double alpha_d, double gamma_d) {
    const real a(alpha_d), g(gamma_d);
    return [=](const real& r2) { return pow(1 + r2 / ((g - 1) * a * a), -g) / (pi() * a * a); };
}

namespace {
real Lambda_r_form(const SlopeDensity& f, double mu_d, bool cut) {
    const real mu(mu_d);
    auto g = [&](const real& r) {
        const real d = r * r - mu * mu;
        // Beyond r = 1e60 (1 + mu) every density but the Student-t's has fallen at least as r^-4, so the rest of the
        // integral is below 1e-60 of it; cutting there keeps pow() from overflowing even the 50-digit exponent range.
        if (d <= 0 || (cut && r > real("1e60") * (1 + mu))) return real(0);
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
}  // namespace

real Lambda(const SlopeDensity& f, double mu_d) { return Lambda_r_form(f, mu_d, true); }

real Lambda_uncut(const SlopeDensity& f, double mu_d) {
    // In u = r / mu, Lambda = 2 mu^2 integral_1^inf f(mu^2 u^2) u (sqrt(u^2 - 1) - acos(1/u)) du: exp-sinh's nodes
    // (1 + e^(pi/2 sinh t)) do not know mu's scale, which they resolve poorly in r at mu = 1e90.
    const real mu(mu_d), mu2 = mu * mu;
    auto g = [&](const real& u) {
        const real d = u * u - 1;
        if (d <= 0) return real(0);
        const real fr = f(mu2 * u * u);
        return fr == 0 ? fr : fr * u * (sqrt(d) - acos(1 / u));
    };
    const real tol("1e-24");
    thread_local boost::math::quadrature::tanh_sinh<real> ts(12);
    thread_local boost::math::quadrature::exp_sinh<real> es(12);
    return 2 * mu2 * (ts.integrate(g, real(1), real(2), tol) + es.integrate(g, real(2), real(INFINITY), tol));
}

real Lambda_student_printed(double alpha_d, double gamma_d, double mu_d) {
    using wide = boost::multiprecision::cpp_bin_float_100;
    const wide g(gamma_d), z = wide(mu_d) / wide(alpha_d), one_half = wide(1) / 2;
    const wide S1 = pow(g - 1 + z * z, 3 * one_half - g) / z;
    thread_local boost::math::quadrature::tanh_sinh<wide> ts;
    const wide S2 =
        ts.integrate([&](const wide& u) { return pow(1 + u * u / (g - 1), one_half - g); }, wide(0), z, wide("1e-60"));
    const wide c =
        boost::math::tgamma(g - one_half) / (sqrt(boost::math::constants::pi<wide>()) * boost::math::tgamma(g));
    return real(c * (pow(g - 1, g) * S1 / (2 * g - 3) + sqrt(g - 1) * S2) - one_half);
}

real Lambda_dimov(int gamma, double alpha_d, double mu_d) {
    using wide = boost::multiprecision::cpp_bin_float_100;
    const wide a(alpha_d), mu(mu_d), A = sqrt(mu * mu + a * a), B = sqrt(mu * mu + 1);
    const wide a2 = a * a, a4 = a2 * a2, a6 = a4 * a2, a8 = a4 * a4;
    switch (gamma) {
        case 0:
            return real((B - mu) / (2 * mu));
        case 1:
            return real((A - B + mu * boost::multiprecision::asinh(mu) - mu * log(mu + A)) / (mu * log(a2)));
        case 2:
            return real((A - mu) / (2 * mu));
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
