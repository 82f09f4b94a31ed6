/// @file
/// smithlab/dcos_law.hpp -- the D cos law of one NDF, templated on it: normals m ~ D(m) cos(theta_m) (Walter 2007
/// sec. 5.3), and Hammon's restriction of it to the normals facing a direction. No virtual call, std::function,
/// allocation or exception in a sample: a sampler that cannot draw returns a NaN vector (no_normal()), which the
/// type-erased samplers (sampling.hpp) turn into input_error.
///
/// The law of s = tan^2(theta_m) is the NDF's analytic survival function Dcos_sf and its inverse Dcos_r2 when it has
/// them at run time (ndf.hpp), else a detail::RadialTable of pi P22(s) (detail/radial_table.hpp); the azimuth is
/// uniform.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "smithlab/detail/radial_table.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/rng.hpp"

namespace smithlab {

/// What a sampler returns when it cannot draw (a law that cannot be drawn in double, or no normal faces the direction).
inline Vec3 no_normal() { return Vec3::Constant(std::numeric_limits<double>::quiet_NaN()); }
/// Rejection loops stop after this many tries and return no_normal() instead of hanging: every loop here accepts with
/// a probability bounded away from 0 for any accepted NDF and direction, so reaching it means a law that cannot be
/// drawn.
inline constexpr long max_tries = 10'000'000;

/// The D cos law of an NDF N: normals m with density D(m) cos(theta_m) (Walter 2007 sec. 5.3), by the NDF's analytic
/// sampler or a detail::RadialTable (the file comment).
template <Ndf N>
class DcosLaw {
public:
    /// tabulate = true tabulates even when the NDF has an analytic sampler (to test the table against it).
    explicit DcosLaw(const N& ndf, bool tabulate = false) : ndf_(ndf) {
        if (tabulate || !has_Dcos_sampler(ndf_))
            table_ = std::make_shared<const detail::RadialTable>(
                [n = ndf_](double s) { return std::numbers::pi * slope_density(n, s); });
    }

    /// P(tan^2 theta_m > s) and its inverse for v in (0, 1].
    /// @{
    double sf(double s) const {
        if constexpr (HasDcosSampler<N>)
            if (!table_) return ndf_.Dcos_sf(s);
        return table_->sf(s);
    }
    double isf(double v) const {
        if constexpr (HasDcosSampler<N>)
            if (!table_) return ndf_.Dcos_r2(v);
        return table_->isf(v);
    }
    /// @}
    /// The slope density P22(s) at s = tan^2(theta_m) (ndf.hpp, slope_density).
    double P22(double s) const { return slope_density(ndf_, s); }
    /// D(m) cos(theta_m) = P22(s) (1 + s)^{3/2} for m.z > 0 (within 1e-50 of the horizon, D(cos) cos), else 0.
    double pdf(const Vec3& m) const {
        if (!(m.z() > 0.0)) return 0.0;
        const double s = tan2_theta(m);
        return s < 1e100 ? P22(s) * (1.0 + s) * std::sqrt(1.0 + s) : ndf_.D(m.z()) * m.z();
    }
    /// A normal m drawn from the law: s by the inverse survival function, the azimuth uniform.
    template <class G>
    Vec3 sample(G& g) const {
        const double s = isf(1.0 - uniform01(g));  // v in (0, 1]: s finite
        return normal_from_slope(s, cos_sin_turn(uniform01(g)));
    }

    /// Whether the law of s is tabulated (a detail::RadialTable) rather than the NDF's own.
    bool tabulated() const { return table_ != nullptr; }
    double table_error() const { return table_ ? table_->error_estimate() : 0.0; }  ///< in probability
    /// The NDF.
    const N& ndf() const { return ndf_; }

private:
    N ndf_;
    std::shared_ptr<const detail::RadialTable> table_;  ///< shared: copies of a law are cheap
};

/// Hammon 2017 ("Intersection normal"): a ray travelling along T = -wi hits a facet drawn from D(m) cos(theta_m)
/// among those with T.m < 0. When T points up (T.z > 0), u1 is shrunk to [F(tan^2 theta_c), 1], theta_c the
/// steepest normal no azimuth can make face the ray, tan theta_c = T.z / |T_xy| (drawn here as v = 1 - u1 in
/// (0, S(tan^2 theta_c)], which keeps the digits when that tail holds 1e-15 of the mass); a rejected m is retried once
/// with its azimuth turned by pi (m_xy -> -m_xy; the slides' "negate phi_m", which must be this map to keep the law:
/// phi -> -phi preserves the facing set only when T lies in the xz-plane, and then does nothing); then start over.
/// For T.z <= 0 plain rejection (more than half of the normals face the ray). wi a unit vector; no_normal() when no
/// normal faces wi (straight down) or none is accepted in max_tries.
template <Ndf N, class G>
Vec3 sample_hammon_normal(const DcosLaw<N>& law, const Vec3& wi, G& g) {
    const Vec3 T = -wi;
    const double Txy2 = T.x() * T.x() + T.y() * T.y();
    if (Txy2 == 0.0 && T.z() > 0.0) return no_normal();
    const double S_c = T.z() > 0.0 ? law.sf(T.z() * T.z() / Txy2) : 1.0;
    if (!(S_c > 0.0)) return no_normal();
    for (long tries = 0; tries < max_tries; ++tries) {
        const double s = law.isf(S_c * (1.0 - uniform01(g)));
        const Vec3 m = normal_from_slope(s, cos_sin_turn(uniform01(g)));
        if (T.dot(m) < 0.0) return m;
        if (T.z() > 0.0) {
            const Vec3 turned(-m.x(), -m.y(), m.z());
            if (T.dot(turned) < 0.0) return turned;
        }
    }
    return no_normal();
}

/// Z(wi) = integral of D cos over wi.m > 0, the normalization of Hammon's restricted law, by a 1D quadrature: for
/// tan(theta_m) = r the azimuths with wi.m > 0 are cos(phi) > -mu / r, mu = cot(theta_i) (signed), a fraction
/// acos(-mu / r) / pi of them.
template <Ndf N>
double hammon_facing_fraction(const DcosLaw<N>& law, const Vec3& wi) {
    const double sin_i = std::hypot(wi.x(), wi.y());
    if (sin_i == 0.0) return wi.z() > 0.0 ? 1.0 : 0.0;
    const double mu = wi.z() / sin_i;
    // Only normals steeper than tan^2 = mu^2 can face away from (mu > 0) or towards (mu < 0) wi: where the D cos
    // mass beyond mu^2 is below double's resolution (wi within ~1e-6 degrees of the normal for alpha = 0.3), Z is 1 or
    // 0 (when that mass is 0) exactly, and the quadrature below would have to find the lobe 700 e-folds from its split.
    const double beyond = law.sf(mu * mu);
    if (mu > 0.0 ? beyond < 1e-17 : beyond == 0.0) return mu > 0.0 ? 1.0 : 0.0;
    auto h = [&](double s) {
        const double c = std::clamp(-mu / std::sqrt(s), -1.0, 1.0);
        return std::acos(c) * law.P22(s);  // (acos / pi) * pi P22
    };
    // Split at the kink s = mu^2, kept inside [1e-300, 1e300] (mu = 5.7e201 at theta_i = 1e-200 degrees).
    return integrate_log_axis(h, {}, mu != 0.0 ? std::clamp(mu * mu, 1e-300, 1e300) : 1.0);
}

}  // namespace smithlab
