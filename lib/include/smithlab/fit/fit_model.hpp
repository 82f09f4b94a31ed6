/// @file
/// smithlab/fit/fit_model.hpp -- a diffuse model (diffuse_model.hpp) against traced data (dataset.hpp): its fit, and
/// its errors on data it never saw.
///
/// The data are the diffuse part (k >= 1 diffuse events) of f(wi, wo) |cos theta_o| at each albedo of a list, all
/// from one trace at albedo 1. A point's values at the albedos share their walks, so they are fitted as one block:
/// residuals W (model - y), W C^-1/2 over the directions of C with variance (the pseudo-inverse: values at several
/// albedos are sums of the same few per-event means, so C may be singular), C their covariance (exact, from the split
/// moments) plus (floor y_a)^2 on the diagonal. floor = 0 is the plain weighted fit (chi^2 / dof near 1 when the
/// model is right); a relative floor (the default: 0.02) says that a cheap model is expected to miss by about that
/// much, so the fit minimizes relative error where the model cannot reach the noise rather than chasing the points
/// traced best.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "smithlab/fit/dataset.hpp"
#include "smithlab/fit/diffuse_model.hpp"
#include "smithlab/fit/least_squares.hpp"

namespace smithlab::fit {

/// The data a diffuse model is fitted to: the traced points, the albedos each is fitted at, the weights' relative
/// floor and the alphas where the fit holds the model energy-bounded.
struct FitData {
    std::vector<DataPoint> points;  ///< eval points (f |cos theta_o|)
    std::vector<double> albedos;    ///< the albedos each point is fitted at
    double floor = 0.02;            ///< relative error floor of the weights
    /// Non-empty: the fit keeps the model energy-bounded, its directional albedo at albedo 1 at most 1 at these alphas
    /// x theta_i in energy_thetas (fit_model).
    std::vector<double> energy_alphas;
};

/// The incidence angles (degrees) where fit_model holds the directional albedo to 1: where the models peak (grazing).
inline const std::vector<double> energy_thetas{0.0, 60.0, 80.0, 89.0};

/// The model's f(wi, wo) |cos theta_o| at a point.
double model_value(const DiffuseModel& m, const std::vector<double>& params, const DataPoint& p, double albedo);

/// Fits m's free constants from its published values. Throws input_error naming the model and `what` (the data's
/// name, e.g. the NDF) when the fit does not converge, the data has too few points for its parameters, or a constant's
/// standard error is not finite (the data does not determine it: naming the constant). With
/// data.energy_alphas, each (alpha, theta_i) adds a residual that is ~0 for E below 1 - 5e-4 and grows as (E - 1) 1e5
/// above 1 (a smooth hinge: fit_model.cpp), E the model's directional albedo at albedo 1 (model_albedo): a penalty that
/// holds the fitted model energy-bounded there (and at lower albedos where each of its albedo^k terms is >= 0). chi^2,
/// dof and the covariance count the data alone: the covariance is the sandwich estimate from the data's exact
/// covariance, the spread of the constants over independent traces (with a floor the weights are not the data's
/// inverse covariance), not how far the model is from the data.
LeastSquaresFit fit_model(const DiffuseModel& m, const FitData& data, const std::string& what);

/// chi^2 / (number of values) of m with these constants on data (weights as in the fit).
double chi2_per_value(const DiffuseModel& m, const std::vector<double>& params, const FitData& data);

/// Relative errors of f |cos theta_o| over every point and albedo whose traced value is positive.
struct RelativeErrors {
    /// The RMS and the largest |model - traced| / traced.
    ///@{
    double rms = 0.0, max = 0.0;
    ///@}
};
/// The relative errors of m with these constants on data.
RelativeErrors relative_errors(const DiffuseModel& m, const std::vector<double>& params, const FitData& data);

/// The model's directional albedo, the integral of f(wi, wo) cos theta_o over the hemisphere of wo, by a product
/// Gauss-Legendre rule (cos theta_o, 20 nodes on each side of cos theta_i, where Oren-Nayar's max and min kink) x
/// midpoint rule (phi_o, 64 over [0, pi] twice: the models are even in phi). Within 1e-4 of EON's closed-form albedo.
double model_albedo(const DiffuseModel& m, const std::vector<double>& params, double alpha, double theta_i,
                    double albedo);

/// The RMS difference of the model's directional albedo and the traced one (albedo points: the sample estimator's
/// diffuse part, k >= 1) over the points and albedos.
double albedo_rms(const DiffuseModel& m, const std::vector<double>& params, const std::vector<DataPoint>& albedo_points,
                  const std::vector<double>& albedos);

/// The largest directional albedo of the model at albedo 1 over alphas x theta_i (degrees), and where: above 1 the
/// model makes energy (not energy-bounded).
struct AlbedoPeak {
    /// The largest directional albedo, and the alpha and theta_i (degrees) where it is.
    ///@{
    double albedo = 0.0, alpha = 0.0, theta_i = 0.0;
    ///@}
};
/// The peak of model_albedo at albedo 1 over alphas x thetas (degrees).
AlbedoPeak max_albedo(const DiffuseModel& m, const std::vector<double>& params, const std::vector<double>& alphas,
                      const std::vector<double>& thetas);

/// Over alphas and a grid of direction pairs (theta 0 to 89 degrees, phi 0 to 180), at albedo 0.5 and 1: the largest
/// |f(wi, wo) - f(wo, wi)| / max(f(wi, wo), f(wo, wi)) (0 for a model symmetric in L and V, as a BRDF must be:
/// Helmholtz reciprocity), and the smallest f (negative: the model is not a BRDF there).
struct GridCheck {
    /// The largest relative asymmetry |f(wi, wo) - f(wo, wi)| / max, and the smallest f.
    ///@{
    double asymmetry = 0.0, min_f = INFINITY;
    ///@}
};
/// The reciprocity and positivity check of m with these constants over alphas and the grid of direction pairs.
GridCheck check_on_grid(const DiffuseModel& m, const std::vector<double>& params, const std::vector<double>& alphas);

}  // namespace smithlab::fit
