#include "smithlab/gtr/interpolants.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <memory>
#include <new>
#include <vector>

#include "smithlab/errors.hpp"
#include "smithlab/gtr/closed_forms.hpp"
#include "smithlab/gtr/spline.hpp"

namespace smithlab {

namespace {
const char* kind_name(GammaInterpolant::Kind k, bool long_form) {
    using K = GammaInterpolant::Kind;
    if (k == K::cspline) return long_form ? "natural cubic spline" : "cspline";
    return k == K::akima ? (long_form ? "Akima spline" : "akima") : (long_form ? "Steffen spline" : "steffen");
}
const char* quantity_name(GammaInterpolant::Quantity q, bool long_form) {
    using Q = GammaInterpolant::Quantity;
    if (q == Q::G1) return long_form ? "G1" : "g1";
    return q == Q::Lambda ? (long_form ? "Lambda" : "lambda") : (long_form ? "log Lambda" : "loglambda");
}
}  // namespace

std::string name_of(const GammaInterpolant& how) {
    return std::string("interp-") + kind_name(how.kind, false) + "-" + quantity_name(how.quantity, false) + "-k" +
        std::to_string(how.max_knot);
}

std::string description_of(const GammaInterpolant& how) {
    return std::string(kind_name(how.kind, true)) + " of " + quantity_name(how.quantity, true) +
        " through the closed forms at gamma = 0.." + std::to_string(how.max_knot) + ", clamped above";
}

double Lambda_gtr_interpolated(double alpha, double gamma, double mu, const GammaInterpolant& how) {
    using Q = GammaInterpolant::Quantity;
    if (how.max_knot < 4 || how.max_knot > gtr_max_closed_gamma)  // message built only on failure: this is a hot path
        require(false, "interpolant max_knot", "in [4, " + std::to_string(gtr_max_closed_gamma) + "]", how.max_knot);
    // Beyond mu in [1e-100, 1e100] the knots are their asymptotes C/mu^2 and E[q+]/mu (closed_forms.cpp), and so is
    // the interpolant: carried out from the end of the range, so that an overflowing Lambda at a knot (mu = 1e-310)
    // is not interpolated into NaN.
    constexpr double big = 1e100, small = 1e-100;
    if (mu > big) return Lambda_gtr_interpolated(alpha, gamma, big, how) * ((big / mu) * (big / mu));
    if (mu < small) return Lambda_gtr_interpolated(alpha, gamma, small, how) * (small / mu);
    const std::size_t n = static_cast<std::size_t>(how.max_knot) + 1;
    std::vector<double> x(n), y(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double L = Lambda_gtr_closed(alpha, static_cast<int>(k), mu);
        x[k] = static_cast<double>(k);
        // log Lambda of an underflowed Lambda is taken at the smallest denormal: finite, and exp() gives 0 back.
        y[k] = how.quantity == Q::G1    ? 1.0 / (1.0 + L)
            : how.quantity == Q::Lambda ? L
                                        : std::log(std::max(L, DBL_TRUE_MIN));
    }
    const gsl_interp_type* type = how.kind == GammaInterpolant::Kind::cspline ? gsl_interp_cspline
        : how.kind == GammaInterpolant::Kind::akima                           ? gsl_interp_akima
                                                                              : gsl_interp_steffen;
    std::unique_ptr<gsl_interp, decltype(&gsl_interp_free)> interp(gsl_interp_alloc(type, n), &gsl_interp_free);
    if (!interp) throw std::bad_alloc();
    gsl_interp_init(interp.get(), x.data(), y.data(), n);
    const double g = std::min(gamma, x.back());
    const double v = gsl_interp_eval(interp.get(), x.data(), y.data(), g, nullptr);
    switch (how.quantity) {
        case Q::G1:
            return Lambda_of_interpolated_G1(v);
        case Q::Lambda:
            return std::max(v, 0.0);  // a spline of Lambda overshoots below 0 (G1 > 1): clamped, as G1 is
        case Q::log_Lambda:
            return std::exp(v);
    }
    return v;
}

}  // namespace smithlab
