// smithlab/sampling.hpp -- microfacet normal samplers. Each returns a normal m and its pdf with respect to solid
// angle; reflected_pdf() turns that into the pdf of the reflected direction. Random numbers come from an Rng the
// caller passes in.
//
//   DcosSampler           m ~ D(m) cos(theta_m) (Walter 2007 sec. 5.3): the NDF's analytic inversion when it has
//                         one (GGX, Beckmann, Blinn: the blog's inversions; GTR: Burley 2012), else a tabulated
//                         inverse CDF of pi P22(tan^2) (radial_table.hpp).
//   VisibleNormalSampler  m ~ D_wi(m) = G1(wi) <wi.m> D(m) / cos(theta_i) (Heitz 2014), for any NDF, exact up to the
//                         tables it reads (radial_table.hpp, lambda_table.hpp).
//   sample_ggx_visible    the same for GGX in closed form (Dupuy & Benyoub 2023, spherical caps).
//   HammonSampler         m ~ D(m) cos(theta_m) restricted to wi.m > 0 (Hammon 2017 appendix, "Intersection normal").
#pragma once

#include <Eigen/Core>
#include <memory>
#include <numbers>

#include "smithlab/geometry.hpp"
#include "smithlab/lambda_table.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/radial_table.hpp"
#include "smithlab/rng.hpp"

namespace smithlab {


struct NormalSample {
    Vec3 m;
    double pdf;  // of m, with respect to solid angle
};


// D(m) = P22 / cos^4 = P22(s) (1 + s)^2 (Walter 2007 eq. 42), from the slope density.
inline double D_from_P22(double P22, double s) { return P22 * (1.0 + s) * (1.0 + s); }

class DcosSampler {
public:
    // tabulate = true tabulates even when the NDF has an analytic sampler (to test the table against it).
    template <Ndf N>
    explicit DcosSampler(const N& ndf, bool tabulate = false)
        : P22_([ndf](double s) { return slope_density(ndf, s); }) {
        if constexpr (HasDcosSampler<N>) {
            if (!tabulate && has_Dcos_sampler(ndf)) {
                sf_ = [ndf](double s) { return ndf.Dcos_sf(s); };
                isf_ = [ndf](double v) { return ndf.Dcos_r2(v); };
                return;
            }
        }
        auto table = std::make_shared<const RadialTable>([P22 = P22_](double s) { return std::numbers::pi * P22(s); });
        sf_ = [table](double s) { return table->sf(s); };
        isf_ = [table](double v) { return table->isf(v); };
        table_error_ = table->error_estimate();
        tabulated_ = true;
    }

    NormalSample sample(Rng& g) const;
    // D(m) cos(theta_m) = P22(s) (1 + s)^{3/2} for m.z > 0, else 0.
    double pdf(const Vec3& m) const;
    // The law of s = tan^2(theta_m): survival function P(tan^2 > s) and its inverse, for v in (0, 1].
    double sf(double s) const { return sf_(s); }
    double isf(double v) const { return isf_(v); }
    double P22(double s) const { return P22_(s); }
    bool tabulated() const { return tabulated_; }
    double table_error() const { return table_error_; }  // in probability; 0 for an analytic sampler

private:
    std::function<double(double)> P22_, sf_, isf_;
    bool tabulated_ = false;
    double table_error_ = 0.0;
};

// Visible normals for any NDF. In slope space, with wi rotated into the xz-plane and mu = cot(theta_i), the visible
// slopes have density P22(x, y) (mu - x)^+ / (mu (1 + Lambda(mu))) (Heitz & d'Eon 2014, eq. 5-6). In polar slope
// coordinates (r, phi) that is P22(r^2) r (mu - r cos phi)^+, which smithlab samples by rejection from
// P22(r^2) r (mu + r) x uniform phi, accepting with (mu - r cos phi)^+ / (mu + r): exact, and the proposal is a
// mixture of the D cos law of r (weight mu / (2 pi)) and the law P22 r^2 dr (weight M = its integral). Acceptance
// mu (1 + Lambda) / (mu + 2 pi M): 1 at normal incidence, 1/pi at grazing.
class VisibleNormalSampler {
public:
    template <Ndf N>
    explicit VisibleNormalSampler(const N& ndf, bool tabulate = false)
        : dcos_(ndf, tabulate),
          Lambda_(std::make_shared<const LambdaTable>(tabulate_Lambda(ndf))),
          r_law_(std::make_shared<const RadialTable>(
              [ndf](double s) { return 0.5 * slope_density(ndf, s) * std::sqrt(s); })) {}

    // wi.z > 0 (input_error otherwise).
    NormalSample sample(const Vec3& wi, Rng& g) const;
    double pdf(const Vec3& wi, const Vec3& m) const;
    double table_error() const;  // the worst of its CDF tables' estimates and the Lambda table's

private:
    DcosSampler dcos_;
    std::shared_ptr<const LambdaTable> Lambda_;
    std::shared_ptr<const RadialTable> r_law_;
};

// GGX visible normals, Dupuy & Benyoub 2023, "Sound and Fast Sampling of Visible GGX Normals with Spherical
// Caps" (listing 3): stretch wi to the alpha = 1 configuration, sample the spherical cap the visible hemisphere
// projects to, add wi, unstretch. wi.z > 0.
NormalSample sample_ggx_visible(double alpha, const Vec3& wi, Rng& g);
// G1(wi) <wi.m> D(m) / cos(theta_i), with GGX's closed-form Lambda.
double pdf_ggx_visible(double alpha, const Vec3& wi, const Vec3& m);

// Hammon 2017 ("Intersection normal"): a ray travelling along T = -wi hits a facet drawn from D(m) cos(theta_m)
// among those with T.m < 0. When T points up (T.z > 0), u1 is shrunk to [F(tan^2 theta_c), 1], theta_c the
// steepest normal no azimuth can make face the ray, tan theta_c = T.z / |T_xy| (smithlab draws v = 1 - u1 from
// (0, S(tan^2 theta_c)], which keeps the digits when that tail holds 1e-15 of the mass); a rejected m is retried once with
// its azimuth turned by pi (m_xy -> -m_xy; the slides' "negate phi_m", which must be this map to keep the law);
// then start over. For T.z <= 0 plain rejection (more than half of the normals face the ray).
class HammonSampler {
public:
    template <Ndf N>
    explicit HammonSampler(const N& ndf, bool tabulate = false) : dcos_(ndf, tabulate) {}

    // input_error when no normal faces wi (wi straight down), or wi is not a unit vector.
    Vec3 sample_normal(const Vec3& wi, Rng& g) const;
    // Z(wi) = integral of D cos over wi.m > 0, by quadrature: the normalization of the restricted law.
    double facing_fraction(const Vec3& wi) const;
    double pdf(const Vec3& wi, const Vec3& m, double Z) const { return wi.dot(m) > 0.0 ? dcos_.pdf(m) / Z : 0.0; }

private:
    DcosSampler dcos_;
};

}  // namespace smithlab
