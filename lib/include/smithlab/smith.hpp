/// @file
/// smithlab/smith.hpp -- the generic Smith engine: P22, P2, Lambda, G1, G2 for any isotropic NDF.
///
/// Notation follows Walter et al. 2007, appendix A, and Hammon 2017, appendix:
///   P22(p, q) = D(m) cos^4(theta_m), tan^2(theta_m) = p^2 + q^2            (Walter eq. 42)
///   P2(q)     = integral over p of P22(p, q)                                (Walter eq. 43)
///   Lambda(mu) = (1/mu) integral_mu^inf (q - mu) P2(q) dq, mu = cot(theta_v) (Walter eq. 48)
///   G1 = 1 / (1 + Lambda),  G2 = 1 / (1 + Lambda_i + Lambda_o)             (Walter eq. 51; Hammon, appendix)
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "smithlab/errors.hpp"
#include "smithlab/grazing.hpp"
#include "smithlab/lambda_fixed.hpp"
#include "smithlab/named.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"

namespace smithlab {

/// How Lambda is computed. `automatic` takes the closed form when the NDF has one, else the fixed rule (below: the
/// reduced 1D integral, 1.4-16x faster than the adaptive routes at 1e-12, which answer where its estimate misses).
/// `fixed` is the reduced 1D integral by fixed Gauss-Kronrod panels on precomputed nodes (lambda_fixed.hpp), the
/// adaptive route (--backend) where its error estimate misses the tolerance. Below the quadrature domain and 1e-8 r0
/// (detail::quadrature_mu_min), `automatic`, `quadrature`, `quadrature2d`, `fixed` answer by the grazing law.
enum class Method { automatic, closed, spline, quadrature, quadrature2d, fixed };
/// The methods by name (`smithlab eval --method NAME`) and what `--list-methods` says of each.
inline constexpr std::array<Named<Method>, 6> method_names = {{
    {Method::automatic, "auto", "closed form where the NDF has one, else the fixed rule (method fixed)"},
    {Method::closed, "closed", "the NDF's closed form (GGX, Beckmann, GTR at integer gamma <= 31, Student-t)"},
    {Method::spline, "spline", "the NDF's spline (GTR: Dimov's natural cubic spline of G1 in gamma)"},
    {Method::quadrature, "quadrature", "reduced 1D quadrature (--backend, --tolerance)"},
    {Method::quadrature2d, "quadrature2d", "nested 2D quadrature P22 -> P2 -> Lambda (--backend, --tolerance)"},
    {Method::fixed, "fixed",
     "reduced 1D quadrature by fixed Gauss-Kronrod panels (precomputed nodes), the --backend route where its error "
     "estimate misses --tolerance"},
}};
Method parse_method(std::string_view name);  ///< throws input_error naming the unknown method
/// The method's name, as method_names spells it.
std::string_view to_string(Method m);

/// Downward directions (mu < 0). Smith's ray-tracing derivation gives Lambda(-mu) = -1 - Lambda(mu);
/// Hammon 2017 (appendix, "Path tracing with Smith masking") redefines it as -Lambda(mu) to make the BRDF symmetric.
enum class Downward { smith, hammon_symmetric };
/// The conventions by name (`smithlab eval --downward NAME`).
inline constexpr std::array<Named<Downward>, 2> downward_names = {{
    {Downward::smith, "smith", "Lambda(-mu) = -1 - Lambda(mu)"},
    {Downward::hammon_symmetric, "hammon", "symmetric, -Lambda(mu)"},
}};
Downward parse_downward(std::string_view name);  ///< throws input_error naming the unknown convention
/// Lambda(-mu) from Lambda(mu) under the convention.
inline double downward_Lambda(double Lambda_up, Downward convention) {
    return convention == Downward::smith ? -1.0 - Lambda_up : -Lambda_up;
}

/// The special values of mu = cot(theta_v), in one place (Lambda, G1 and G2 below, the variants' prepare, eval).
/// mu must be a number: NaN is refused ("mu is NaN").
inline void require_mu_number(double mu) {
    if (std::isnan(mu)) throw input_error("mu is NaN");
}
/// Lambda(|mu|), from Lambda_up = Lambda at a finite mu > 0: |mu| = 0 (grazing) gives +inf and |mu| = inf (normal) 0,
/// without a call to Lambda_up.
template <class F>
double Lambda_of_abs(double mu, const F& Lambda_up) {
    require_mu_number(mu);
    const double a = std::abs(mu);
    return a == 0.0 ? INFINITY : std::isinf(a) ? 0.0 : Lambda_up(a);
}
/// Lambda(mu) from Lambda(|mu|): a direction below (mu < 0) follows the convention.
inline double Lambda_of_sign(double mu, double Lambda_of_abs_mu, Downward convention) {
    return mu < 0.0 ? downward_Lambda(Lambda_of_abs_mu, convention) : Lambda_of_abs_mu;
}
/// Lambda at any mu (both of the above).
template <class F>
double Lambda_at(double mu, Downward convention, const F& Lambda_up) {
    return Lambda_of_sign(mu, Lambda_of_abs(mu, Lambda_up), convention);
}

/// How Lambda is computed: the method, the quadrature library and tolerance where it integrates, and the convention for
/// downward directions.
struct LambdaOptions {
    /// The route (the closed form where there is one, by default).
    Method method = Method::automatic;
    /// The quadrature library of the quadrature methods.
    Backend backend = Backend::boost;
    double tolerance = 1e-12;  ///< relative, for the quadrature methods
    /// Lambda of a downward direction (mu < 0).
    Downward downward = Downward::smith;
};

/// The form of G2: height-correlated (Heitz 2014 eq. 99 and 101) or uncorrelated, G1(wi) G1(wo) (Walter 2007 eq. 23;
/// Heitz 2014 eq. 98).
enum class G2Form { height_correlated, uncorrelated };

namespace detail {
/// tan(t) - t without cancellation, given tan_t = tan(t): Taylor series
/// (tan t = sum 2^{2k}(2^{2k}-1)|B_2k| t^{2k-1}/(2k)!) below 0.5, where the difference would cancel.
double tan_minus_x(double t, double tan_t);
/// Lambda_1d / Lambda_2d take mu in [1e-12, 1e12]; Lambda() handles 0, inf and the sign.
void require_mu(double mu);
/// Below it the quadrature methods answer by the grazing law (grazing.hpp), for P22(0) = P22_at_pole: the quadratures'
/// lower end 1e-12 (1e-12 r0 where r0 > 1), capped at 1e-8 r0, where the law's error is at double rounding.
double quadrature_mu_min(double P22_at_pole);
/// ... and mu >= 1e-12 r0, r0 = 1 / sqrt(pi P22(0)) the NDF's core slope scale (alpha for GGX and Beckmann; at most
/// ~1 for GTR and Blinn-Phong): the grazing peak of the integrand sits at pi/2 - t ~ mu / alpha, and below
/// mu / alpha ~ 1e-13 Boost's tanh-sinh steps over it (GGX(1e49) at mu = 0.5 came out 1.85e48 for 1e49; Beckmann at
/// alpha = 18, mu = 1e-12 60 % low), and the nested route takes minutes. GSL holds further; the rule is the tested one.
void require_quadrature_scale(double mu, double P22_at_pole, const char* method);
/// ... and, for an NDF that has only D (its slope form derived through cos theta_m), r0 >= 1e-3: cos theta_m carries a
/// slope r ~ r0 only to 1e-16 / r0^2 relative (sin^2 = (1 - c)(1 + c)), which put 2.3e-9 into Lambda at r0 = 1e-4,
/// 0.43 at 1e-8 and 1e164 at 1e-50 (tests/test_domain.cpp); at 1e-3 it is 2e-11.
void require_slope_digits(double P22_at_pole, const char* method);
}  // namespace detail

/// input_error unless the quadrature methods (Lambda_1d, Lambda_2d) accept mu for ndf; `method` names them in the
/// message. For callers that validate a whole grid before they compute any of it.
template <Ndf N>
void require_quadrature_domain(const N& ndf, double mu, const char* method = "quadrature") {
    detail::require_mu(mu);
    const double P22_at_pole = slope_density(ndf, 0.0);
    if (!has_slope_density(ndf)) detail::require_slope_digits(P22_at_pole, method);
    detail::require_quadrature_scale(mu, P22_at_pole, method);
}

/// P22(p, q), Walter 2007 eq. 42.
template <Ndf N>
double P22(const N& ndf, double p, double q) {
    return slope_density(ndf, p * p + q * q);
}

namespace detail {
/// Where the t-form integrands of P2, Lambda_1d and Lambda_2d at a = |q| or mu have their grazing features, in
/// s = pi/2 - t (integrate_quarter_turn's breaks): s = a / r for the slope scales r = r0 = 1/sqrt(pi P22(0)) (the core)
/// and r = 1 (a GTR or Blinn-Phong tail bending, tan theta_m = 1). Only below s = 1e-3: above, a feature spans a
/// thousandth of the interval and more, which both backends resolve unaided (the misses were all below 5e-6), and a
/// break there costs GSL up to 2x.
template <Ndf N>
std::array<double, 2> grazing_breaks(const N& ndf, double a) {
    const double r0 = core_slope_scale(ndf);
    auto small = [](double s) { return s < 1e-3 ? s : 0.0; };  // 0: no break
    return {small(a / r0), small(a)};
}
}  // namespace detail

/// P2(q) = 2 integral_0^inf P22(p, q) dp, Walter 2007 eq. 43 (P22 is even in p), in p = |q| tan u:
///   P2(q) = 2 |q| integral_0^{pi/2} f(q^2 sec^2 u) sec^2 u du.
/// Below |q| = 1e-150, where q^2 would underflow, P2(q) = P2(0) to O(q^2) and is integrated as such, in log p.
template <Ndf N>
double P2(const N& ndf, double q, const QuadratureOptions& opts = {}) {
    if (std::abs(q) < 1e-150)
        return 2.0 * integrate_log_axis([&](double p) { return slope_density(ndf, p * p); }, opts);
    const double q2 = q * q;
    return 2.0 * std::abs(q) *
        integrate_quarter_turn(
               [&](double, double, double sec2) {
                   const double r2 = q2 * sec2;
                   if (!(r2 < INFINITY)) return 0.0;
                   const double f = slope_density(ndf, r2);
                   return f == 0.0 ? 0.0 : f * sec2;
               },
               opts, detail::grazing_breaks(ndf, std::abs(q)));
}

/// Lambda by the book: the nested route P22 -> P2 -> Lambda, Walter 2007 eq. 48. Cost: milliseconds.
/// In q = mu sec v: Lambda = mu integral_0^{pi/2} (sec v - 1) sec v tan v P2(mu sec v) dv,
/// with sec v - 1 = tan^2 v / (sec v + 1) to keep the digits near v = 0.
template <Ndf N>
double Lambda_2d(const N& ndf, double mu, const QuadratureOptions& opts = {}) {
    require_quadrature_domain(ndf, mu, "quadrature2d");
    QuadratureOptions inner = opts;
    inner.tolerance = opts.tolerance * 0.1;
    return mu *
        integrate_quarter_turn(
               [&](double, double tn, double sec2) {
                   const double sec = std::sqrt(sec2), q = mu * sec;
                   if (!(q < INFINITY)) return 0.0;
                   const double p2 = P2(ndf, q, inner);
                   return p2 == 0.0 ? 0.0 : sec / (sec + 1.0) * (tn * (tn * (tn * p2)));
               },
               opts, detail::grazing_breaks(ndf, mu));
}

/// Lambda by the reduced route. Doing the azimuthal integral of Walter eq. 48 in closed form (docs/math.md):
///   Lambda(mu) = (2/mu) integral_mu^inf f(r^2) r (sqrt(r^2 - mu^2) - mu acos(mu/r)) dr,   f(r^2) = P22,
/// and with r = mu sec t,
///   Lambda(mu) = 2 mu^2 integral_0^{pi/2} f(mu^2 sec^2 t) sec^2 t tan t (tan t - t) dt,
/// a bounded integrand on a finite interval; the factor mu^2 sec^2 t = r^2 is carried inside, so that neither a
/// huge nor a tiny mu overflows. At grazing angles the peak of f sits at pi/2 - t ~ mu/alpha (integrate_quarter_turn).
template <Ndf N>
double Lambda_1d(const N& ndf, double mu, const QuadratureOptions& opts = {}) {
    require_quadrature_domain(ndf, mu);
    const double mu2 = mu * mu;
    return 2.0 *
        integrate_quarter_turn(
               [&](double t, double tn, double sec2) {
                   const double r2 = mu2 * sec2;
                   if (!(r2 < INFINITY)) return 0.0;
                   const double f = slope_density(ndf, r2);
                   return f == 0.0 ? 0.0 : f * r2 * tn * detail::tan_minus_x(t, tn);
               },
               opts, detail::grazing_breaks(ndf, mu));
}

/// The same integral by the fixed rule of lambda_fixed.hpp (Gauss-Kronrod 15-31 panels in u = acosh(r/mu) on
/// precomputed nodes, with QUADPACK's error estimate): where that estimate meets opts.tolerance its value, else
/// Lambda_1d's by opts.backend. Same domain as Lambda_1d.
template <Ndf N>
double Lambda_fixed(const N& ndf, double mu, const QuadratureOptions& opts = {}) {
    require_quadrature_domain(ndf, mu, "fixed");
    require(opts.tolerance > 0.0 && opts.tolerance < 1.0, "quadrature tolerance", "in (0, 1)", opts.tolerance);
    const FixedLambda r = Lambda_fixed_rule(ndf, mu, opts.tolerance);
    return r.converged ? r.Lambda : Lambda_1d(ndf, mu, opts);
}

namespace detail {
/// Whether opts.method answers ndf at a finite mu > 0 by the grazing law: a quadrature route (`automatic` where there
/// is no closed form) below its domain.
template <Ndf N>
bool answers_by_grazing_law(const N& ndf, double mu, const LambdaOptions& opts) {
    const bool quadrature = opts.method == Method::quadrature || opts.method == Method::quadrature2d ||
        opts.method == Method::fixed || (opts.method == Method::automatic && !has_closed_Lambda(ndf));
    return quadrature && mu < quadrature_mu_min(slope_density(ndf, 0.0));
}

/// Lambda at a finite mu > 0 by opts.method; `law` (may be null) holds the NDF's grazing law once computed.
template <Ndf N>
double Lambda_by_method(const N& ndf, double mu, const LambdaOptions& opts, GrazingLawOnce* law = nullptr) {
    const QuadratureOptions q{opts.backend, opts.tolerance};
    if (answers_by_grazing_law(ndf, mu, opts)) return Lambda_grazing(law ? law->get(ndf, q) : grazing_law(ndf, q), mu);
    switch (opts.method) {
        case Method::automatic:
            if (has_closed_Lambda(ndf)) break;
            return Lambda_fixed(ndf, mu, q);
        case Method::closed:
            if (!has_closed_Lambda(ndf)) throw input_error("method 'closed': this ndf has no closed-form Lambda");
            break;
        case Method::spline:
            if constexpr (HasSplineLambda<N>) {
                if (has_spline_Lambda(ndf)) return ndf.Lambda_spline(mu);
            }
            throw input_error("method 'spline': this ndf has no spline Lambda");
        case Method::quadrature:
            return Lambda_1d(ndf, mu, q);
        case Method::quadrature2d:
            return Lambda_2d(ndf, mu, q);
        case Method::fixed:
            return Lambda_fixed(ndf, mu, q);
    }
    if constexpr (HasClosedLambda<N>) return ndf.Lambda(mu);
    throw input_error("this ndf has no closed-form Lambda");
}
}  // namespace detail

/// Lambda(mu) for mu = cot(theta_v): mu = +inf gives 0, mu = 0 gives +inf, mu < 0 follows opts.downward.
template <Ndf N>
double Lambda(const N& ndf, double mu, const LambdaOptions& opts = {}) {
    return Lambda_at(mu, opts.downward, [&](double a) { return detail::Lambda_by_method(ndf, a, opts); });
}

/// G1 = 1 / (1 + Lambda(mu)), Walter 2007 eq. 51 with mu = |cot theta_v| (eq. 44): a direction below the
/// macrosurface is masked as if seen from its own side, as in transmission. Below the quadrature domain, and wherever
/// Lambda overflows at mu != 0 (c/mu beyond DBL_MAX, any method), by the grazing law's own G1 (grazing.hpp).
template <Ndf N>
double G1(const N& ndf, double mu, const LambdaOptions& opts = {}) {
    require_mu_number(mu);
    const double a = std::abs(mu);
    const QuadratureOptions q{opts.backend, opts.tolerance};
    if (a > 0.0 && a < INFINITY && detail::answers_by_grazing_law(ndf, a, opts))
        return G1_grazing(grazing_law(ndf, q), a);
    const double L = Lambda_of_abs(mu, [&](double m) { return detail::Lambda_by_method(ndf, m, opts); });
    return L == INFINITY && a > 0.0 ? G1_grazing(grazing_law(ndf, q), a) : 1.0 / (1.0 + L);
}

/// mu = cot(theta) of c = cos(theta): c / sqrt((1 - c)(1 + c)), sin^2 without the cancellation of 1 - c^2 near c = 1.
/// c is clamped to [-1, 1] (rounding); c = 1 gives inf, c = 0 gives 0, c < 0 a negative mu.
inline double mu_of_cos(double c) {
    c = c > 1.0 ? 1.0 : c < -1.0 ? -1.0 : c;
    return c / std::sqrt((1.0 - c) * (1.0 + c));
}

/// Lambda and G1 from c = cos(theta_v) instead of mu (a renderer holds the cosine), for any NDF: through mu_of_cos,
/// with Lambda's and G1's conventions (c < 0: below the surface). Ggx (ndfs.hpp) and Gtr at gamma = 0..4 (gtr.hpp)
/// overload these with forms written in c itself, a root and a division cheaper and exact at c -> 0 and c -> 1.
/// @{
template <Ndf N>
double Lambda_from_cos(const N& ndf, double c, const LambdaOptions& opts = {}) {
    return Lambda(ndf, mu_of_cos(c), opts);
}
template <Ndf N>
double G1_from_cos(const N& ndf, double c, const LambdaOptions& opts = {}) {
    return G1(ndf, mu_of_cos(c), opts);
}
/// @}

/// Bidirectional shadowing-masking. Same side (reflection): height-correlated 1/(1 + Lambda_i + Lambda_o)
/// (Hammon 2017 appendix, "Solving for G2") or uncorrelated G1 G1 (Walter 2007 eq. 23).
/// Opposite sides (transmission), height-correlated: with u = f(height) uniform, the point is seen from above with
/// probability u^Lambda_i and from below with (1 - u)^Lambda_o, so G2 = Beta(1 + Lambda_i, 1 + Lambda_o)
/// (Heitz 2014, "Understanding the masking-shadowing function", section on transmission).
double G2_from_Lambdas(double Lambda_i, double Lambda_o, bool same_side, G2Form form);

/// G2 of `ndf` for the directions mu_i = cot(theta_i) and mu_o = cot(theta_o), of either sign (opposite signs:
/// transmission), by G2_from_Lambdas on Lambda(|mu|) of the method in `opts`.
template <Ndf N>
double G2(const N& ndf, double mu_i, double mu_o, G2Form form = G2Form::height_correlated,
          const LambdaOptions& opts = {}) {
    require_mu_number(mu_i);
    require_mu_number(mu_o);
    const auto up = [&](double a) { return detail::Lambda_by_method(ndf, a, opts); };
    const bool same_side = (mu_i >= 0.0) == (mu_o >= 0.0);
    return G2_from_Lambdas(Lambda_of_abs(mu_i, up), Lambda_of_abs(mu_o, up), same_side, form);
}

}  // namespace smithlab
