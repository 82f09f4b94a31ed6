/// @file
/// smithlab/fast_lambda.hpp -- Lambda of one NDF at the cost of a closed form, for the code that calls it per sample
/// or per bounce (samplers, the microsurface walk): the NDF's closed form when it has one (checked at run time, so that
/// GTR at a non-integer gamma takes the other branch), else its LambdaTable (lambda_table.hpp), built once here.
/// Read-only after construction, so any number of threads may call it; no call throws (NaN in, NaN out).
///
/// The walk asks for Lambda of a direction, which it has as tan^2(theta) = (x^2 + y^2) / z^2 without a root:
/// at_tan2(t). For GGX (the capability ggx_alpha(), ndf.hpp) that is Heitz 2014 eq. 72 in t itself,
///     Lambda = (sqrt(1 + alpha^2 t) - 1) / 2 = alpha^2 t / (2 (1 + sqrt(1 + alpha^2 t)))   (no cancellation),
/// one root and one division; every other NDF a detail::Tan2Spline of its Lambda (detail/tan2_spline.hpp: a cubic
/// picked by the bits of t, within 1e-7 of the table or closed form it is built from, 1e-12 absolute where Lambda <
/// 1e-5), and mu = 1 / sqrt(t) where that does not answer (tan(theta) outside [2^-20, 2^20]). Its step needs 1 / Lambda
/// (upward) and 1 / (1 + Lambda) (downward, Smith's convention): for GGX, with d2 = x^2 + y^2, |z| and R = sqrt(z^2 +
/// alpha^2 d2),
///     1 / Lambda = 2 (z^2 + |z| R) / (alpha^2 d2),   1 / (1 + Lambda) = 2 |z| / (|z| + R),
/// since sqrt(1 + alpha^2 t) = R / |z| and 1 + Lambda = (1 + R / |z|) / 2: one root and one division each.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "smithlab/detail/tan2_spline.hpp"
#include "smithlab/lambda_table.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

/// num / den, for a caller that may compare it (x < num / den as x den < num, den >= 0) before it divides.
struct Quotient {
    /// The numerator and the denominator.
    /// @{
    double num, den;
    /// @}
    /// num / den.
    double value() const { return num / den; }
};

/// Lambda of an NDF N at the cost of a closed form, for the walk and the samplers: the closed form, else a LambdaTable;
/// in tan^2, GGX's form or a detail::Tan2Spline (the file comment).
template <Ndf N>
class FastLambda {
public:
    /// Builds what `ndf` needs: its LambdaTable (options `table`) where it has no closed form, and the
    /// detail::Tan2Spline unless it is GGX.
    explicit FastLambda(const N& ndf, const LambdaTableOptions& table = {}) : ndf_(ndf) {
        if (!has_closed_Lambda(ndf_)) table_.emplace(tabulate_Lambda(ndf_, table));
        const double a = ggx_alpha(ndf_);
        if (a > 0.0 && a < INFINITY) ggx_alpha2_ = a * a;
        else
            spline_ = std::make_shared<const detail::Tan2Spline>(
                [this](double t) { return (*this)(1.0 / std::sqrt(t)); }, spline_tolerance, spline_floor);
    }

    /// Lambda(mu) for mu >= 0 (mu = 0: inf; mu = inf: 0). Downward directions are the caller's convention
    /// (smith.hpp, downward_Lambda).
    double operator()(double mu) const {
        if (table_) return table_->Lambda(mu);
        if (!(mu > 0.0)) return mu == 0.0 ? INFINITY : std::numeric_limits<double>::quiet_NaN();
        if (mu == INFINITY) return 0.0;
        if constexpr (HasClosedLambda<N>) return ndf_.Lambda(mu);  // the closed form (smithlab::Lambda's route)
        else return smithlab::Lambda(ndf_, mu);                    // unreachable: no closed form means a table
    }

    /// Lambda at tan^2(theta) = t >= 0, i.e. mu = 1 / sqrt(t) (t = 0: 0; t = inf: inf).
    double at_tan2(double t) const {
        if (ggx_alpha2_ > 0.0) {
            const double q = ggx_alpha2_ * t;
            if (q < 1e300) return q / (2.0 * (1.0 + std::sqrt(1.0 + q)));  // else (t = inf, alpha^2 t overflows) by mu
        } else if (const double L = (*spline_)(t); L == L) {
            return L;
        }
        return (*this)(1.0 / std::sqrt(t));
    }

    /// 1 / Lambda and 1 / (1 + Lambda) of the direction with x^2 + y^2 = d2 and |z| = az, both > 0 and not so small
    /// that their squares lose digits (d2 > 1e-300, az > 1e-150), as quotients num / den (num > 0, den >= 0): the
    /// walk's escape test compares against them without dividing (microsurface.hpp, next_height).
    Quotient inv_Lambda(double d2, double az) const {
        if (ggx_alpha2_ > 0.0) {
            const double z2 = az * az, a2d2 = ggx_alpha2_ * d2;
            return {2.0 * (z2 + az * std::sqrt(z2 + a2d2)), a2d2};  // a2d2 = 0 (underflow): inf, Lambda = 0
        }
        return {1.0, at_tan2(d2 / (az * az))};
    }
    /// 1 / (1 + Lambda) of that direction, the same way.
    Quotient inv_1p_Lambda(double d2, double az) const {
        if (ggx_alpha2_ > 0.0) return {2.0 * az, az + std::sqrt(az * az + ggx_alpha2_ * d2)};
        return {1.0, 1.0 + at_tan2(d2 / (az * az))};
    }
    /// The walk's Lambda against the route it is built from: within 1e-7 relative where Lambda >= 1e-5, 1e-12 absolute
    /// below (an escape probability C1^Lambda moves by |ln C1| 1e-12 there).
    /// @{
    static constexpr double spline_tolerance = 1e-7, spline_floor = 1e-5;
    /// @}

    /// Whether Lambda comes from a table (no closed form).
    bool tabulated() const { return table_.has_value(); }
    /// Relative, of the walk's Lambda: the table's estimate (or 0 for a closed form) plus the spline's tolerance.
    double error_estimate() const {
        return (table_ ? table_->error_estimate() : 0.0) + (spline_ ? spline_tolerance : 0.0);
    }
    /// The NDF.
    const N& ndf() const { return ndf_; }

private:
    N ndf_;
    std::optional<LambdaTable> table_;
    double ggx_alpha2_ = 0.0;                           ///< > 0: GGX of this alpha^2, Lambda in closed form in tan^2
    std::shared_ptr<const detail::Tan2Spline> spline_;  ///< every other NDF
};

}  // namespace smithlab
