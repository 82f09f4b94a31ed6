#include "smithlab/quadrature.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "smithlab/errors.hpp"

namespace smithlab {

Backend parse_backend(std::string_view name) {
    if (name == "boost") return Backend::boost;
    if (name == "gsl") return Backend::gsl;
    throw input_error("unknown quadrature backend '" + std::string(name) + "' (expected boost or gsl)");
}

std::string_view to_string(Backend b) { return b == Backend::boost ? "boost" : "gsl"; }

namespace {

// Boost.Math double-exponential quadrature: tanh-sinh on [a, b], exp-sinh on [a, inf). Their nodes crowd the
// end points doubly exponentially, which is where the stiff features of smithlab's integrands sit (a grazing-angle
// peak at s ~ mu/alpha, the pole of a peaked D), and their cost is bounded by the refinement level, unlike a
// recursive bisection that can run away when round-off keeps the error estimate above the tolerance.
// The integrators hold only their node tables, built once per thread.
double integrate_boost(FunctionRef f, double a, double b, double tol) {
    auto g = [&](double x) { return f(x); };
    try {
        if (std::isinf(b)) {
            thread_local boost::math::quadrature::exp_sinh<double> exp_sinh;  // Boost 1.74: integrate() is not const
            return exp_sinh.integrate(g, a, b, tol);
        }
        thread_local boost::math::quadrature::tanh_sinh<double> tanh_sinh;
        return tanh_sinh.integrate(g, a, b, tol);
    } catch (const boost::math::evaluation_error& e) {
        throw std::runtime_error(std::string("quadrature (boost): the integrand is not finite: ") + e.what());
    }
}

// GSL QAG / QAGIU. GSL's default error handler aborts the process; it is switched off only for the duration
// of the call and the caller's handler restored. GSL refuses epsrel below 50 eps when epsabs = 0.
double integrate_gsl(FunctionRef f, double a, double b, double tol) {
    constexpr std::size_t limit = 1000;
    std::unique_ptr<gsl_integration_workspace, decltype(&gsl_integration_workspace_free)> ws(
        gsl_integration_workspace_alloc(limit), &gsl_integration_workspace_free);
    if (!ws) throw std::bad_alloc();
    gsl_function F;
    F.function = [](double x, void* p) { return (*static_cast<FunctionRef*>(p))(x); };
    F.params = &f;
    const double epsrel = std::max(tol, 1.2e-14);
    double result = 0.0, abserr = 0.0;
    gsl_error_handler_t* previous = gsl_set_error_handler_off();
    if (std::isinf(b))
        gsl_integration_qagiu(&F, a, 0.0, epsrel, limit, ws.get(), &result, &abserr);
    else
        gsl_integration_qag(&F, a, b, 0.0, epsrel, limit, GSL_INTEG_GAUSS21, ws.get(), &result, &abserr);
    gsl_set_error_handler(previous);
    // A status of GSL_EROUND (round-off limits the error estimate) still comes with the best estimate, which is
    // what we want at tolerances near machine precision; accuracy is established by the tests, not the status.
    return result;
}

}  // namespace

double integrate(FunctionRef f, double a, double b, const QuadratureOptions& opts) {
    if (!(a < b)) return 0.0;
    require(opts.tolerance > 0.0 && opts.tolerance < 1.0, "quadrature tolerance", "in (0, 1)", opts.tolerance);
    const double r = opts.backend == Backend::boost ? integrate_boost(f, a, b, opts.tolerance)
                                                    : integrate_gsl(f, a, b, opts.tolerance);
    if (!std::isfinite(r))
        throw std::runtime_error("quadrature (" + std::string(to_string(opts.backend)) + ") did not converge to a finite value");
    return r;
}

}  // namespace smithlab
