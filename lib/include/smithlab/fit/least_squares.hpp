/// @file
/// smithlab/fit/least_squares.hpp -- weighted nonlinear least squares, for the diffuse fitter.
///
/// Minimizes chi^2 = |r(p)|^2 over the parameters p, where the caller's residuals r are already whitened (a residual
/// divided by its standard error, or a block of correlated residuals multiplied by the inverse square root of its
/// covariance: fit/fit_model.hpp). GSL's multifit_nlinear does the work: Levenberg-Marquardt in a trust region (More
/// 1978) with a finite-difference Jacobian, chosen over Ceres (a dependency for a problem of at most ten parameters and
/// 1e4 residuals) and Eigen's unsupported LevenbergMarquardt (no covariance, no documented stopping rule); GSL is a
/// dependency already, and gsl_multifit_nlinear_covar gives (J^T J)^-1 at the solution.
///
/// The parameters' standard errors here are sqrt(diag((J^T J)^-1)) times sqrt(chi^2 / dof) when that is above 1: the
/// residuals' scale estimated from the misfit (the Birge ratio). A caller whose weights are not the data's inverse
/// covariance (fit_model: a relative floor, penalty rows) recomputes them from the Jacobian and residuals returned.
/// A residual that is not finite (a model outside its domain) counts as 1e150: the step that led there is refused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace smithlab::fit {

/// r = residuals(p): writes all of r.
using ResidualFn = std::function<void(std::span<const double> p, std::span<double> r)>;

/// When the nonlinear least-squares solver (GSL's trust-region Levenberg-Marquardt) stops.
struct LeastSquaresOptions {
    /// The most iterations before it gives up (converged = false).
    int max_iterations = 500;
    double xtol = 1e-8;  ///< GSL's tests: the step relative to p, the gradient relative to chi^2
    /// The gradient test's tolerance (see xtol).
    double gtol = 1e-8;
};

/// What a least-squares fit found: the parameters, their standard errors and covariance, the residuals, chi^2, and
/// whether it converged.
struct LeastSquaresFit {
    /// The parameters at the solution, and their standard errors sqrt(diag(covariance) max(1, chi^2 / dof)).
    /// @{
    std::vector<double> params, stderr_;
    /// @}
    std::vector<double> covariance;  ///< (J^T J)^-1, p x p row by row, unscaled
    std::vector<double> jacobian;    ///< J at the solution, residuals x p row by row
    std::vector<double> residuals;   ///< r at the solution
    /// The sum of the squared residuals at the solution.
    double chi2 = 0.0;
    std::int64_t dof = 0;  ///< residuals - parameters
    /// The iterations taken.
    int iterations = 0;
    /// Whether the solver met its tolerances (else `reason`).
    bool converged = false;
    std::string reason;  ///< why not, when not
    /// chi^2 / dof, 0 where dof <= 0.
    double chi2_dof() const { return dof > 0 ? chi2 / static_cast<double>(dof) : 0.0; }
};

/// Refuses (converged = false, reason) fewer residuals than parameters plus one; never throws for a bad model.
LeastSquaresFit least_squares(std::size_t residuals, std::vector<double> start, const ResidualFn& r,
                              const LeastSquaresOptions& options = {});

}  // namespace smithlab::fit
