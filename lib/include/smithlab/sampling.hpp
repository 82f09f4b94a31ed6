/// @file
/// smithlab/sampling.hpp -- microfacet normal samplers behind one type, for any NDF: each holds the NDF as an AnyNdf
/// and is a thin wrapper over a template (one algorithm, templated on the NDF, for the code that knows its type:
/// dcos_law.hpp, visible_normals.hpp). Each returns a normal m and its pdf with respect to solid angle, checks its
/// input (input_error naming it), and turns a sampler that cannot draw into input_error; reflected_pdf()
/// (geometry.hpp) turns the pdf into that of the reflected direction. Random numbers come from an Rng the caller
/// passes in.
///
///   DcosSampler           m ~ D(m) cos(theta_m) (Walter 2007 sec. 5.3): DcosLaw.
///   VisibleNormalSampler  m ~ D_wi(m) = <wi.m>^+ D(m) / A(wi) for wi anywhere on the sphere (= G1(wi) <wi.m> D(m) /
///                         cos(theta_i) above the horizon, Heitz 2014): VisibleNormals, the rejection route unless
///                         asked for the automatic one (closed forms by capability).
///   sample_ggx_visible    the same for GGX in closed form (Dupuy & Benyoub 2023, spherical caps).
///   HammonSampler         m ~ D(m) cos(theta_m) restricted to wi.m > 0 (Hammon 2017 appendix, "Intersection normal").
#pragma once

#include <memory>

#include "smithlab/any_ndf.hpp"
#include "smithlab/dcos_law.hpp"
#include "smithlab/detail/radial_table.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/lambda_table.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/rng.hpp"
#include "smithlab/visible_normals.hpp"

namespace smithlab {

/// A normal drawn by a sampler, with its density.
struct NormalSample {
    /// The unit normal, m.z > 0.
    Vec3 m;
    double pdf;  ///< of m, with respect to solid angle
};

/// Normals m ~ D(m) cos(theta_m) of any NDF, held type-erased (DcosLaw of AnyNdf: the NDF's analytic sampler, or a
/// table).
class DcosSampler {
public:
    /// tabulate = true tabulates even when the NDF has an analytic sampler (to test the table against it).
    template <Ndf N>
    explicit DcosSampler(const N& ndf, bool tabulate = false) : law_(as_any(ndf), tabulate) {}

    /// A normal and its pdf.
    NormalSample sample(Rng& g) const;
    /// D(m) cos(theta_m) = P22(s) (1 + s)^{3/2} for m.z > 0, else 0.
    double pdf(const Vec3& m) const { return law_.pdf(m); }
    /// The law of s = tan^2(theta_m): survival function P(tan^2 > s) and its inverse, for v in (0, 1].
    /// @{
    double sf(double s) const { return law_.sf(s); }
    double isf(double v) const { return law_.isf(v); }
    /// @}
    /// The NDF's slope density at s = tan^2(theta_m).
    double P22(double s) const { return law_.P22(s); }
    /// Whether the law of s is tabulated.
    bool tabulated() const { return law_.tabulated(); }
    double table_error() const { return law_.table_error(); }  ///< in probability; 0 for an analytic sampler

private:
    DcosLaw<AnyNdf> law_;
};

/// Visible normals of any NDF for a direction anywhere on the sphere, held type-erased (VisibleNormals of AnyNdf).
class VisibleNormalSampler {
public:
    /// tabulate: the rejection route with the D cos law tabulated too; else the rejection route, for any NDF.
    template <Ndf N>
    explicit VisibleNormalSampler(const N& ndf, bool tabulate = false)
        : VisibleNormalSampler(ndf, tabulate ? VisibleRoute::tabulated : VisibleRoute::rejection) {}
    /// The visible normals of `ndf` by `route` (VisibleRoute).
    template <Ndf N>
    VisibleNormalSampler(const N& ndf, VisibleRoute route)
        : normals_(std::make_shared<const VisibleNormals<AnyNdf>>(as_any(ndf), route)) {}

    /// Any unit wi with A(wi) > 0; input_error when wi is not a unit vector or no normal is visible from it (straight
    /// down, or a projected area that underflows: Beckmann(1e-3) seen from 10 degrees below the horizon).
    NormalSample sample(const Vec3& wi, Rng& g) const;
    /// D_wi(m) = <wi.m>^+ D(m) / A(wi) (visible_normals.hpp).
    double pdf(const Vec3& wi, const Vec3& m) const { return normals_->pdf(wi, m); }
    /// A(wi), Smith's projected area over the whole sphere.
    double projected_area(const Vec3& wi) const { return normals_->projected_area(wi); }
    /// The worst of its tables' error estimates (VisibleNormals::table_error).
    double table_error() const { return normals_->table_error(); }

private:
    std::shared_ptr<const VisibleNormals<AnyNdf>> normals_;
};

/// GGX visible normals in closed form (detail/visible_normals_closed.hpp), any unit wi with A(wi) > 0 (input_error
/// otherwise).
NormalSample sample_ggx_visible(double alpha, const Vec3& wi, Rng& g);
/// <wi.m>^+ D(m) / A(wi), with GGX's closed-form Lambda.
double pdf_ggx_visible(double alpha, const Vec3& wi, const Vec3& m);

/// Hammon's sampler (dcos_law.hpp, sample_hammon_normal), with its normalization Z(wi) by quadrature.
class HammonSampler {
public:
    /// The D cos law of `ndf` (tabulate: a table even where the NDF has an analytic sampler).
    template <Ndf N>
    explicit HammonSampler(const N& ndf, bool tabulate = false) : law_(as_any(ndf), tabulate) {}

    /// input_error when no normal faces wi (wi straight down), or wi is not a unit vector.
    Vec3 sample_normal(const Vec3& wi, Rng& g) const;
    /// Z(wi) = integral of D cos over wi.m > 0: the normalization of the restricted law.
    double facing_fraction(const Vec3& wi) const;
    /// The density D(m) cos(theta_m) / Z of the restricted law at m, 0 where wi.m <= 0; Z from facing_fraction(wi).
    double pdf(const Vec3& wi, const Vec3& m, double Z) const { return wi.dot(m) > 0.0 ? law_.pdf(m) / Z : 0.0; }

private:
    DcosLaw<AnyNdf> law_;
};

}  // namespace smithlab
