#include "smithlab/fit/least_squares.hpp"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace smithlab::fit {

namespace {

struct Problem {
    const ResidualFn* r;
    std::vector<double> p, out;  // contiguous copies: GSL passes strided views (a Jacobian column, for one)
};

int residuals(const gsl_vector* x, void* data, gsl_vector* f) {
    auto& pr = *static_cast<Problem*>(data);
    for (std::size_t i = 0; i < pr.p.size(); ++i) pr.p[i] = gsl_vector_get(x, i);
    (*pr.r)(pr.p, pr.out);
    for (std::size_t i = 0; i < pr.out.size(); ++i) gsl_vector_set(f, i, std::isfinite(pr.out[i]) ? pr.out[i] : 1e150);
    return GSL_SUCCESS;
}

// The solution, its residuals, Jacobian and covariance, and the standard errors (scaled by the Birge ratio where it is
// above 1), read from the workspace after the driver; true when all of them are finite.
bool read_solution(gsl_multifit_nlinear_workspace* w, std::size_t n, LeastSquaresFit& out) {
    const std::size_t p = out.params.size();
    std::unique_ptr<gsl_matrix, decltype(&gsl_matrix_free)> covar(gsl_matrix_alloc(p, p), gsl_matrix_free);
    out.iterations = static_cast<int>(gsl_multifit_nlinear_niter(w));
    const gsl_vector* sol = gsl_multifit_nlinear_position(w);
    for (std::size_t i = 0; i < p; ++i) out.params[i] = gsl_vector_get(sol, i);
    const gsl_vector* f = gsl_multifit_nlinear_residual(w);
    gsl_blas_ddot(f, f, &out.chi2);
    const gsl_matrix* J = gsl_multifit_nlinear_jac(w);
    gsl_multifit_nlinear_covar(J, 0.0, covar.get());
    out.jacobian.resize(n * p);
    out.residuals.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        out.residuals[i] = gsl_vector_get(f, i);
        for (std::size_t j = 0; j < p; ++j) out.jacobian[i * p + j] = gsl_matrix_get(J, i, j);
    }
    out.covariance.resize(p * p);
    out.stderr_.resize(p);
    const double scale = std::max(1.0, out.chi2_dof());
    bool finite = std::isfinite(out.chi2) && out.chi2 < 1e290;
    for (std::size_t i = 0; i < p; ++i) {
        for (std::size_t j = 0; j < p; ++j) out.covariance[i * p + j] = gsl_matrix_get(covar.get(), i, j);
        out.stderr_[i] = std::sqrt(std::max(0.0, out.covariance[i * p + i]) * scale);
        finite = finite && std::isfinite(out.params[i]) && std::isfinite(out.stderr_[i]);
    }
    return finite;
}

// converged, or the reason why not, from the driver's status and whether the solution is finite.
void set_outcome(int status, bool finite, const LeastSquaresOptions& options, LeastSquaresFit& out) {
    if (status != GSL_SUCCESS) {
        out.reason = status == GSL_EMAXITER
            ? "no convergence in " + std::to_string(options.max_iterations) + " iterations"
            : std::string("stopped: ") + gsl_strerror(status);
    } else if (!finite) {
        out.reason = "the solution or its covariance is not finite (a parameter the data does not determine?)";
    } else {
        out.converged = true;
    }
}

}  // namespace

LeastSquaresFit least_squares(std::size_t n, std::vector<double> start, const ResidualFn& r,
                              const LeastSquaresOptions& options) {
    gsl_set_error_handler_off();  // idempotent; failures come back as status codes
    LeastSquaresFit out;
    const std::size_t p = start.size();
    out.params = start;
    out.dof = static_cast<std::int64_t>(n) - static_cast<std::int64_t>(p);
    if (p == 0 || out.dof < 1) {
        out.reason = std::to_string(n) + " residuals for " + std::to_string(p) + " parameters (need at least " +
            std::to_string(p + 1) + ")";
        return out;
    }
    Problem problem{&r, std::vector<double>(p), std::vector<double>(n)};
    gsl_multifit_nlinear_fdf fdf{};
    fdf.f = residuals;
    fdf.df = nullptr;  // forward differences
    fdf.fvv = nullptr;
    fdf.n = n;
    fdf.p = p;
    fdf.params = &problem;
    gsl_multifit_nlinear_parameters params = gsl_multifit_nlinear_default_parameters();
    params.scale = gsl_multifit_nlinear_scale_more;
    std::unique_ptr<gsl_multifit_nlinear_workspace, decltype(&gsl_multifit_nlinear_free)> w(
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, n, p), gsl_multifit_nlinear_free);
    std::unique_ptr<gsl_vector, decltype(&gsl_vector_free)> x(gsl_vector_alloc(p), gsl_vector_free);
    for (std::size_t i = 0; i < p; ++i) gsl_vector_set(x.get(), i, start[i]);
    if (int s = gsl_multifit_nlinear_init(x.get(), &fdf, w.get()); s != GSL_SUCCESS) {
        out.reason = std::string("could not start: ") + gsl_strerror(s);
        return out;
    }
    int info = 0;
    const int status = gsl_multifit_nlinear_driver(static_cast<std::size_t>(options.max_iterations), options.xtol,
                                                   options.gtol, 0.0, nullptr, nullptr, &info, w.get());
    set_outcome(status, read_solution(w.get(), n, out), options, out);
    return out;
}

}  // namespace smithlab::fit
