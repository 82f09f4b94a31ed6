// smithlab/visible_normals.hpp -- visible normals of a direction anywhere on the sphere, for one NDF, templated on
// it (no virtual call, std::function or allocation in a sample): what the microsurface walk draws its hit normals from.
//
// For a unit v the law is D_v(m) = <v.m>^+ D(m) / A(v) over m.z > 0, with the projected area
//     A(v) = (1 + Lambda(v)) cos(theta_v)  over the whole sphere, Lambda(-mu) = -1 - Lambda(mu)
// (Heitz, Hanika, d'Eon, Dachsbacher 2016, sec. 4.2): for v below the horizon A(v) = Lambda(|mu|) |v.z|.
// In slope space, with v turned into the xz-plane and mu = cot(theta_v) of either sign, the visible slopes have
// density P22(x, y) (mu - x)^+ (Heitz & d'Eon 2014, eq. 5-6). Sampled exactly by rejection:
//   mu > 0: from P22 r (mu + r) x uniform phi, a mixture of the D cos law of r and the law P22 r^2 dr, accepting
//           with (mu - x)^+ / (mu + r) (the algorithm of VisibleNormalSampler, sampling.hpp);
//   mu < 0: only slopes r > |mu| can face v: from the law P22 r^2 dr truncated to r > |mu| (its survival drawn in
//           (0, S(mu^2)]) x uniform phi, accepting with (mu - x)^+ / r <= 1. Its acceptance stays O(1) for tails
//           P22 ~ r^-4 (GGX, GTR); for a Gaussian tail (Beckmann) it falls as |mu| / alpha grows, where a ray's
//           chance to hit, Lambda(|mu|), falls as exp(-mu^2 / alpha^2).
#pragma once

#include <algorithm>
#include <cmath>
#include <concepts>
#include <memory>
#include <numbers>
#include <optional>

#include "smithlab/fast_lambda.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/radial_table.hpp"
#include "smithlab/rng.hpp"

namespace smithlab {

// The D cos law of s = tan^2(theta_m): the NDF's analytic survival function and inverse when it has them (at run
// time), else a RadialTable of pi P22 (radial_table.hpp).
template <Ndf N>
class DcosLaw {
public:
    explicit DcosLaw(const N& ndf) : ndf_(ndf) {
        if (!has_Dcos_sampler(ndf_))
            table_ = std::make_shared<const RadialTable>([n = ndf_](double s) { return std::numbers::pi * slope_density(n, s); });
    }
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
    double P22(double s) const { return slope_density(ndf_, s); }
    const N& ndf() const { return ndf_; }

private:
    N ndf_;
    std::shared_ptr<const RadialTable> table_;
};

// Capability: an NDF that is GGX of some alpha (ggx_alpha() >= 0; NaN when a type is GGX only at some parameters).
template <class N>
concept HasGgxAlpha = requires(const N& n) {
    { n.ggx_alpha() } -> std::convertible_to<double>;
};

// GGX visible normals in closed form, any v with A(v) > 0: Dupuy & Benyoub 2023, "Sound and Fast Sampling of Visible
// GGX Normals with Spherical Caps", listing 3: stretch v to alpha = 1, where D_v is the clamped cosine about v; a
// uniform point u of the sphere's cap u.z > -v.z, added to v, is m.z > 0 distributed so; unstretch. For v below the
// horizon the cap is (|v.z|, 1]: the same formula.
template <class G>
Vec3 sample_ggx_visible_normal(double alpha, const Vec3& v, G& g) {
    const Vec3 vs = Vec3(alpha * v.x(), alpha * v.y(), v.z()).normalized();
    const double phi = 2.0 * std::numbers::pi * uniform01(g);
    const double z = (1.0 - uniform01(g)) * (1.0 + vs.z()) - vs.z();
    const double sin_t = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
    const Vec3 h(sin_t * std::cos(phi) + vs.x(), sin_t * std::sin(phi) + vs.y(), std::max(z + vs.z(), 0x1p-1000));
    return Vec3(alpha * h.x(), alpha * h.y(), h.z()).normalized();
}

template <Ndf N>
class VisibleNormals {
public:
    explicit VisibleNormals(const N& ndf)
        : dcos_(ndf), Lambda_(ndf),
          r_law_(std::make_shared<const RadialTable>([ndf](double s) { return 0.5 * slope_density(ndf, s) * std::sqrt(s); })) {}

    // A normal m (m.z > 0, v.m > 0) from D_v, for a unit v with A(v) > 0 (v not straight down).
    template <class G>
    Vec3 sample(const Vec3& v, G& g) const {
        constexpr double pi = std::numbers::pi;
        if constexpr (HasGgxAlpha<N>) {
            const double alpha = dcos_.ndf().ggx_alpha();
            if (alpha >= 0.0) return sample_ggx_visible_normal(alpha, v, g);
        }
        const double sin_v = std::sqrt(v.x() * v.x() + v.y() * v.y());
        if (sin_v == 0.0) return from_slope(dcos_.isf(1.0 - uniform01(g)), 2.0 * pi * uniform01(g));  // D cos
        const double mu = v.z() / sin_v, cos_phi = v.x() / sin_v, sin_phi = v.y() / sin_v;
        const double p_dcos = mu > 0.0 ? mu / (mu + 2.0 * pi * r_law_->total()) : 0.0;
        const double tail = mu > 0.0 ? 1.0 : r_law_->sf(mu * mu);  // the mass of r > |mu| when v points down
        for (long tries = 0;; ++tries) {
            const double u = 1.0 - uniform01(g);
            const double s = mu > 0.0 && uniform01(g) < p_dcos ? dcos_.isf(u) : r_law_->isf(tail * u);
            const double r = std::sqrt(s), phi = 2.0 * pi * uniform01(g);
            const double x = r * std::cos(phi), y = r * std::sin(phi);
            // accept with (mu - x)^+ / (mu + r) upward, (mu - x)^+ / r downward (x < mu < 0 there)
            const double bound = mu > 0.0 ? mu + r : r;
            if (uniform01(g) * bound >= mu - x && tries < max_tries) continue;
            const double n = 1.0 / std::sqrt(1.0 + s);
            return {(-x * cos_phi + y * sin_phi) * n, (-x * sin_phi - y * cos_phi) * n, n};
        }
    }

    // D_v(m) = <v.m>^+ D(m) / A(v).
    double pdf(const Vec3& v, const Vec3& m) const {
        const double vm = v.dot(m);
        if (!(m.z() > 0.0 && vm > 0.0)) return 0.0;
        return vm * D(m) / projected_area(v);
    }

    // A(v) = (1 + Lambda) v.z upward, Lambda(|mu|) |v.z| downward; both |mu| Lambda(|mu|) |v_xy| + max(v.z, 0).
    double projected_area(const Vec3& v) const {
        const double sin_v = std::sqrt(v.x() * v.x() + v.y() * v.y());
        if (sin_v == 0.0) return v.z() > 0.0 ? 1.0 : 0.0;
        const double a = std::max(std::abs(v.z() / sin_v), 1e-300);  // mu Lambda(mu) -> E[q+] as mu -> 0
        return a * Lambda_(a) * sin_v + std::max(v.z(), 0.0);
    }

    // D(m) from the slope form, D = P22 (1 + s)^2 (Walter 2007 eq. 42); 0 for m.z <= 0.
    double D(const Vec3& m) const {
        if (!(m.z() > 0.0)) return 0.0;
        const double s = (m.x() * m.x() + m.y() * m.y()) / (m.z() * m.z());
        return dcos_.P22(s) * (1.0 + s) * (1.0 + s);
    }

    const FastLambda<N>& Lambda() const { return Lambda_; }
    const DcosLaw<N>& dcos() const { return dcos_; }

private:
    // A rejection loop that cannot accept within this many tries (a law that cannot be drawn in double) returns its
    // last proposal rather than hang: it never happens for an accepted NDF and direction (acceptance >= 1/pi upward).
    static constexpr long max_tries = 10'000'000;
    static Vec3 from_slope(double s, double phi) {
        const double c = 1.0 / std::sqrt(1.0 + s), sn = std::sqrt(s) * c;
        return {sn * std::cos(phi), sn * std::sin(phi), c};
    }

    DcosLaw<N> dcos_;
    FastLambda<N> Lambda_;
    std::shared_ptr<const RadialTable> r_law_;
};

}  // namespace smithlab
