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
    if (const Named<Backend>* b = find_named(backend_names, name)) return b->value;
    throw input_error("unknown quadrature backend '" + std::string(name) + "' (expected " +
                      join_names(backend_names, ", ", " or ") + ")");
}

std::string_view to_string(Backend b) { return name_of(backend_names, b); }

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

// GSL QAG / QAGIU report a failure to meet the tolerance (GSL_EROUND, routine near 1e-12; GSL_EMAXITER, ..) through
// GSL's error handler, whose default aborts the process; it is one process-wide pointer. Setting it off and back
// around each call raced as soon as two threads integrated (one thread's restore re-armed the abort under the
// other's call), so it is switched off once, at the first GSL integration: a function-local static is initialized
// exactly once, and every later call happens after it (C++11 [stmt.dcl]/4). Every status is then returned (and
// ignored, below). GSL refuses epsrel below 50 eps when epsabs = 0.
void switch_gsl_handler_off_once() {
    static const bool off = (gsl_set_error_handler_off(), true);
    (void)off;
}

double integrate_gsl(FunctionRef f, double a, double b, double tol) {
    switch_gsl_handler_off_once();
    constexpr std::size_t limit = 1000;
    std::unique_ptr<gsl_integration_workspace, decltype(&gsl_integration_workspace_free)> ws(
        gsl_integration_workspace_alloc(limit), &gsl_integration_workspace_free);
    if (!ws) throw std::bad_alloc();
    gsl_function F;
    F.function = [](double x, void* p) { return (*static_cast<FunctionRef*>(p))(x); };
    F.params = &f;
    const double epsrel = std::max(tol, 1.2e-14);
    double result = 0.0, abserr = 0.0;
    if (std::isinf(b)) gsl_integration_qagiu(&F, a, 0.0, epsrel, limit, ws.get(), &result, &abserr);
    else gsl_integration_qag(&F, a, b, 0.0, epsrel, limit, GSL_INTEG_GAUSS21, ws.get(), &result, &abserr);
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
        throw std::runtime_error("quadrature (" + std::string(to_string(opts.backend)) +
                                 ") did not converge to a finite value");
    return r;
}

}  // namespace smithlab
