#include "smithlab/compensation/compensation.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fresnel.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::compensation {

namespace {

using std::numbers::pi;
// Globally adaptive Gauss-Kronrod (GSL's QAG through smithlab's integrate: each call has its own workspace, so the
// nested integrals here are safe). Boost's adaptive Gauss-Kronrod halves the absolute tolerance with every level of
// its recursion instead, which round-off in a nested integrand never meets: 2^depth panels.
template <class F>
double gk(const F& f, double a, double b, double tolerance) {
    return integrate(f, a, b, {Backend::gsl, tolerance});
}

// The same in x = a + (b - a) S(u), S(u) = u^2 (3 - 2u): flat at both ends, so that a square-root end becomes linear
// in u.
template <class F>
double smooth_gk(const F& f, double a, double b, double tolerance) {
    const double L = b - a;
    return gk([&](double u) { return f(a + L * u * u * (3.0 - 2.0 * u)) * L * 6.0 * u * (1.0 - u); }, 0.0, 1.0,
              tolerance);
}

// One scattering event of the grazing limit: a reflection (facets of reflectance F, null: 1), or a refraction through
// a dielectric facet of relative index eta (the index below over the index above: light comes from above; light from
// inside a medium of index n is eta = 1 / n), weighted by 1 - F, F the exact dielectric Fresnel (fresnel.hpp).
struct Event {
    bool transmission = false;
    double eta = 1.0;
    G2Form form = G2Form::height_correlated;
};

// The z of the direction refracted through a facet of normal m (m.z = mz), wi.m = c, wi.z = ci, eta the index below
// over the index above (Walter et al. 2007, eq. 40: wt = (c / eta - cos_t) m - wi / eta, cos_t = sqrt(1 - (1 - c^2) /
// eta^2)); 1 (not downward) under total internal reflection.
double refracted_z(double c, double mz, double ci, double eta) {
    const double k = 1.0 - (1.0 - c) * (1.0 + c) / (eta * eta);
    if (!(k > 0.0)) return 1.0;
    return (c / eta - std::sqrt(k)) * mz - ci / eta;
}

// Lambda of an outgoing direction of height z (either side of the surface), through |cot theta|.
double Lambda_of_z(FunctionRef Lambda, double z) {
    const double s = std::sqrt((1.0 - z) * (1.0 + z));
    return s > 0.0 ? Lambda(std::abs(z) / s) : 0.0;
}

// The grazing limit (mu -> 0) of the albedo of one event, wi = x: G2 / cos_i -> g(wo) / E[q+] with g = 1 for the
// height-correlated G2 of a reflection (1 / (1 + Lambda_i + Lambda_o) ~ 1 / Lambda_i, Lambda_i cos_i -> E[q+]), g =
// G1(wo) for the separable one, and, in transmission, g = G1(wo) separable and 0 height-correlated (B(1 + Lambda_i,
// 1 + Lambda_o) ~ Gamma(1 + Lambda_o) Lambda_i^-(1 + Lambda_o): light grazing the top of the surface does not reach
// below it). wi.m = r cos phi / sqrt(1 + r^2); every normal with cos phi > 0 reflects upward and refracts downward:
//     E(0) = integral_{p > 0} P22 p w(m) g(wo(m)) dp dq / integral_{p > 0} P22 p dp dq,
// w = F(wi.m) in reflection, 1 - F in transmission; in r = tan t (t in [0, pi/2]) and phi in [0, pi/2] (even in phi).
double grazing_albedo(FunctionRef P22, FunctionRef Lambda, const FunctionRef* F, const Event& event, double tolerance) {
    if (event.transmission && event.form == G2Form::height_correlated) return 0.0;
    // A dielectric event from inside (eta < 1; in reflection F is then the dielectric one): its weight has a
    // square-root kink at the critical angle, wi.m = sin t cos phi = sqrt(1 - eta^2), split there in phi and in t.
    const double c_crit = event.eta < 1.0 ? std::sqrt((1.0 - event.eta) * (1.0 + event.eta)) : 1.0;
    auto radial = [&](double t, bool weighted) {
        if (t >= pi / 2) return 0.0;
        const double r = std::tan(t), c = std::cos(t), w = r * r * P22(r * r) / (c * c);  // r^2 P22 dr/dt
        if (!weighted || w == 0.0) return w;
        const double sin_m = std::sin(t);
        auto weight = [&](double phi) {
            const double cm = sin_m * std::cos(phi);  // wi.m
            const double f = event.transmission ? fresnel_dielectric(cm, event.eta) : F ? (*F)(cm) : 1.0;
            const double wo_z = event.transmission ? refracted_z(cm, c, 0.0, event.eta) : 2.0 * cm * c;
            if (event.transmission ? !(wo_z < 0.0) : !(wo_z > 0.0)) return 0.0;
            const double g = event.form == G2Form::uncorrelated ? 1.0 / (1.0 + Lambda_of_z(Lambda, wo_z)) : 1.0;
            return std::cos(phi) * (event.transmission ? 1.0 - f : f) * g;
        };
        if (!(sin_m > c_crit)) return w * gk(weight, 0.0, pi / 2, 0.1 * tolerance);
        const double phi_c = std::acos(c_crit / sin_m);
        return w * (smooth_gk(weight, 0.0, phi_c, 0.1 * tolerance) + smooth_gk(weight, phi_c, pi / 2, 0.1 * tolerance));
    };
    auto numerator = [&](double t) { return radial(t, true); };
    auto denominator = [&](double t) { return radial(t, false); };  // times the integral of cos phi
    // The inclinations in panels [10^-(k+1), 10^-k], k = 0..8, below 1 (and split at the critical angle's t_c): the
    // slope law's mass may sit anywhere from t ~ 1e-8 to pi/2 (Beckmann at alpha 1e-4 has none beyond t ~ 1e-3, where
    // one rule over [0, pi/2] sees only zeros), and no panel is wider than ten times its distance from 0.
    const double t_c = std::asin(c_crit);
    std::vector<double> edges{0.0};
    for (int k = 9; k >= 1; --k) edges.push_back(std::pow(10.0, -k));
    edges.push_back(1.0);
    if (c_crit < 1.0) edges.push_back(t_c);
    edges.push_back(pi / 2);
    std::sort(edges.begin(), edges.end());
    double num = 0.0, den = 0.0;
    for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
        const double a = edges[k], b = edges[k + 1];
        if (!(b > a)) continue;
        num += c_crit < 1.0 ? smooth_gk(numerator, a, b, tolerance) : gk(numerator, a, b, tolerance);
        den += gk(denominator, a, b, tolerance);
    }
    return num / den;
}

// E of one reflection at mu in (0, 1]: the quadrature of the header over [0, r1] x [0, pi] and {r1 < r < r_max,
// |phi| < phi_max(r)}.
double reflection_albedo(FunctionRef P22, FunctionRef Lambda, const FunctionRef* F, double mu, double tolerance,
                         G2Form form, double slope_scale) {
    const double ci = mu, si = std::sqrt((1.0 - mu) * (1.0 + mu));
    const double Li = si > 0.0 ? Lambda(ci / si) : 0.0;
    // The integrand at (r, phi), without the measure r P22(r^2): (cos_i + sin_i r cos phi) G2 F, 0 below the horizon.
    auto facet = [&](double r, double cos_phi) {
        const double a = ci + si * r * cos_phi, n2 = 1.0 + r * r;               // a = (wi . m) sqrt(n2)
        const double woz = (ci * (1.0 - r * r) + 2.0 * si * r * cos_phi) / n2;  // wo = 2 (wi.m) m - wi
        if (!(woz > 0.0 && a > 0.0)) return 0.0;
        const double g = a * G2_from_Lambdas(Li, Lambda_of_z(Lambda, woz), true, form);
        return F ? g * (*F)(a / std::sqrt(n2)) : g;
    };
    const double inner_tol = 0.1 * tolerance;
    // [0, r1] x [0, pi]: every azimuth reflects above the horizon.
    const double r1 = ci / (1.0 + si), rmax = (1.0 + si) / ci;
    auto radial = [&](double r) {
        const double w = r * P22(r * r);
        if (w == 0.0) return 0.0;
        return w * gk([&](double phi) { return facet(r, std::cos(phi)); }, 0.0, pi, inner_tol);
    };
    double full = 0.0, lo = 0.0;
    for (double hi = slope_scale; hi > 0.0 && hi < r1; lo = hi, hi *= 4.0) full += gk(radial, lo, hi, tolerance);
    full += gk(radial, lo, r1, tolerance);
    // (r1, rmax): |phi| < phi_max(r), cos phi_max = -cos_i (1 - r^2) / (2 sin_i r); r = r1 (rmax / r1)^S(u),
    // S(u) = u^2 (3 - 2u): logarithmic in r (rmax / r1 = ((1 + sin_i) / cos_i)^2 grows without bound at grazing
    // incidence, and the slope law's features are O(1) wide in ln r), flat at both ends (dS/du = 0 there).
    double part = 0.0;
    if (si > 0.0 && rmax > r1) {
        const double L = 2.0 * std::log((1.0 + si) / ci);
        part = gk(
            [&](double u) {
                const double r = r1 * std::exp(L * u * u * (3.0 - 2.0 * u)), dr = r * L * 6.0 * u * (1.0 - u);
                const double w = r * P22(r * r) * dr;
                if (!(w > 0.0) || !(r > 0.0)) return 0.0;
                const double phi_max = std::acos(std::clamp(-ci * (1.0 - r * r) / (2.0 * si * r), -1.0, 1.0));
                if (!(phi_max > 0.0)) return 0.0;
                return w * phi_max * gk([&](double t) { return facet(r, std::cos(phi_max * t)); }, 0.0, 1.0, inner_tol);
            },
            0.0, 1.0, tolerance);
    }
    return 2.0 * (full + part) / ci;
}

// ---- Dielectric facets: reflection and transmission in one pass over the normals that see wi ----
//
// E_R and E_T (Walter et al. 2007, eqs. 20 and 21 integrated over wo: the Jacobians, eqs. 14 and 17, cancel against
// dwo), (1 / cos_i) integral D(m) (wi.m) {F, 1 - F} G2 dm, F the dielectric Fresnel (eq. 22), in t = theta_m and
// the azimuth phi from wi's, where D(m) dm = P22(tan^2 t) tan t / cos^2 t dt dphi (eq. 42):
//     {E_R, E_T} = (2 / cos_i) integral_0^{pi/2} P22 tan t / cos^2 t integral_0^pi (c / cos t) {F G2_R, (1 - F) G2_T},
// c = wi.m = cos_i cos t + sin_i sin t cos phi, each over its side of its horizon. For a fixed t every kink of the
// inner integrand is a value of c, so a closed-form phi (c is monotone in phi); see dielectric_albedos below.

struct Albedos {
    double R = 0.0, T = 0.0;
};

// The 21-point Gauss-Kronrod rule on [-1, 1] and its embedded 10-point Gauss rule (Boost.Math's tables: the
// non-negative half of the nodes, x = 0 first; the Gauss nodes are those of odd index).
struct Kronrod21 {
    std::array<double, 21> x{}, wk{}, wg{};
};
const Kronrod21& kronrod21() {
    static const Kronrod21 rule = [] {
        using GK = boost::math::quadrature::gauss_kronrod<double, 21>;
        using G = boost::math::quadrature::gauss<double, 10>;
        Kronrod21 r;
        r.wk[10] = GK::weights()[0];
        for (int i = 1; i <= 10; ++i)
            for (int side : {-1, 1}) {
                r.x[10 + side * i] = side * GK::abscissa()[i];
                r.wk[10 + side * i] = GK::weights()[i];
                r.wg[10 + side * i] = i % 2 == 1 ? G::weights()[i / 2] : 0.0;
            }
        return r;
    }();
    return rule;
}

struct Panel {
    double a = 0.0, b = 0.0;
    Albedos value, error;
};

// One panel of both components, with QUADPACK's error estimate (Piessens et al. 1983, "QUADPACK", qk21, as GSL's
// QAG uses it): |K - G| scaled by resasc as min(1, (200 |K - G| / resasc)^1.5), no less than 50 eps resabs.
template <class F>
Panel kronrod_panel(const F& f, double a, double b) {
    const Kronrod21& q = kronrod21();
    const double mid = 0.5 * (a + b), h = 0.5 * (b - a);
    std::array<Albedos, 21> y;
    for (int k = 0; k < 21; ++k) y[k] = f(mid + h * q.x[k]);
    Panel p{a, b, {}, {}};
    for (double Albedos::*m : {&Albedos::R, &Albedos::T}) {
        double kronrod = 0.0, gauss = 0.0, resabs = 0.0, resasc = 0.0;
        for (int k = 0; k < 21; ++k) {
            kronrod += q.wk[k] * (y[k].*m);
            gauss += q.wg[k] * (y[k].*m);
            resabs += q.wk[k] * std::abs(y[k].*m);
        }
        for (int k = 0; k < 21; ++k) resasc += q.wk[k] * std::abs((y[k].*m) - 0.5 * kronrod);
        const double hh = std::abs(h);
        double err = std::abs((kronrod - gauss) * h);
        resasc *= hh;
        resabs *= hh;
        if (resasc != 0.0 && err != 0.0) err = resasc * std::min(1.0, std::pow(200.0 * err / resasc, 1.5));
        constexpr double eps = std::numeric_limits<double>::epsilon();
        if (resabs > std::numeric_limits<double>::min() / (50.0 * eps)) err = std::max(50.0 * eps * resabs, err);
        p.value.*m = kronrod * h;
        p.error.*m = err;
    }
    return p;
}

// integral_0^n f over the pieces [i, i + 1], globally adaptive (the panel whose error is the largest part of its
// component's allowance is halved) until each component's estimated error is within tolerance of its value, or
// max_panels.
template <class F>
Albedos adapt(const F& f, int n, double tolerance, int max_panels) {
    std::vector<Panel> panels;
    panels.reserve(static_cast<std::size_t>(n) + 8);
    for (int i = 0; i < n; ++i) panels.push_back(kronrod_panel(f, i, i + 1.0));
    Albedos value, error;
    for (;;) {
        value = {}, error = {};
        for (const Panel& p : panels) {
            value.R += p.value.R, value.T += p.value.T;
            error.R += p.error.R, error.T += p.error.T;
        }
        const double allow_R = tolerance * std::abs(value.R), allow_T = tolerance * std::abs(value.T);
        if ((error.R <= allow_R && error.T <= allow_T) || static_cast<int>(panels.size()) >= max_panels) break;
        std::size_t worst = 0;
        double most = -1.0;
        for (std::size_t i = 0; i < panels.size(); ++i) {
            const double e = std::max(error.R > allow_R ? panels[i].error.R / allow_R : 0.0,
                                      error.T > allow_T ? panels[i].error.T / allow_T : 0.0);
            if (e > most) most = e, worst = i;
        }
        const Panel p = panels[worst];
        const double mid = 0.5 * (p.a + p.b);
        if (!(mid > p.a && mid < p.b)) break;
        panels[worst] = kronrod_panel(f, p.a, mid);
        panels.push_back(kronrod_panel(f, mid, p.b));
    }
    return value;
}

// G2 of a transmission, wi above and wt below: B(1 + Lambda_i, 1 + Lambda_o) height-correlated (Heitz 2014,
// "Understanding the masking-shadowing function", eq. 101), G1 G1 separable; G2_from_Lambdas's, with the beta
// function in double (Boost's default promotes it to long double, 30x the time, for 1e-14).
double G2_across(double Lambda_i, double Lambda_o, G2Form form) {
    if (form == G2Form::uncorrelated) return 1.0 / ((1.0 + Lambda_i) * (1.0 + Lambda_o));
    if (std::isinf(Lambda_i) || std::isinf(Lambda_o)) return 0.0;
    using namespace boost::math::policies;
    return boost::math::beta(1.0 + Lambda_i, 1.0 + Lambda_o, policy<promote_double<false>>());
}

// E_R and E_T at mu in (0, 1], light above an interface of relative index eta (below over above): the functions below,
// down to dielectric_albedos_at.
//
// The inner integral, at t: c runs over [c0 - s, c0 + s], c0 = cos_i cos t, s = sin_i sin t, phi = acos((c - c0) /
// s). Its break points are the values of c where the integrand has a kink:
//   - the reflected horizon, wr.z = 2 c cos t - cos_i = 0 (wr = 2 c m - wi, Walter eq. 39): R lives above it;
//   - eta < 1: the critical angle c_crit = sqrt(1 - eta^2), below which F = 1 (eq. 22's g is imaginary) and T = 0,
//     above which F and cos theta_t = g / eta are analytic in sqrt(c - c_crit); and the refracted horizon,
//     wt.z = ((c - g) cos t - cos_i) / eta = 0 (eq. 40), where g = c - cos_i / cos t >= 0, squared:
//     c_t = (cos_i^2 + cos^2 t (1 - eta^2)) / (2 cos t cos_i), a crossing where c_t cos t >= cos_i and c_t >= c_crit
//     (T lives above it; for eta >= 1 the coefficient of m in wt is negative and wt.z < 0 throughout);
//   - eta >= 1: c = 0, the normals that see wi;
//   - for a narrow slope law (r0 = 1 / sqrt(pi P22(0)), the core slope scale, < 0.2), the layers where the outgoing
//     direction's G1 changes (its Lambda does where cot theta ~ r0): wr.z = k r0 and wt.z = -k r0, k = 1, 4, 16.
// On the side c >= c_crit the variable is w, c = c_crit + D sin^2 w, D = c0 + s - c_crit: sqrt(c - c_crit) and
// sqrt(c0 + s - c) are both analytic in w, and dphi = 2 sqrt(D) sin w dw / sqrt(c - (c0 - s)); elsewhere phi,
// analytic at both ends 0 and pi. Ends where the integrand is not analytic are flattened by a quadratic map: the
// refracted horizon (G2 = B(1 + L_i, 1 + L_o) ~ |wt.z|^(1 + L_i), L_o ~ 1 / |wt.z|), and phi = pi in w (the
// Jacobian's inverse square root).
// The outer integral's break points are the t where an inner one enters or leaves [0, pi] (c = cos(t -+ theta_i)
// at phi = 0, pi) or two of them meet: pi/4 -+ theta_i / 2 (the reflected horizon); pi/2 - theta_i (c = 0, eta >= 1);
// theta_i + theta_c, |theta_c - theta_i| (the critical angle, cos theta_c = c_crit); atan((+-sin_i +- eta) /
// cos_i), the refracted horizon at phi = 0 (upper sign of sin_i) or pi, the roots of cos_i^2 tan^2 t -+ 2 cos_i
// sin_i tan t + 1 - eta^2 - cos_i^2 = 0, where they are crossings; cos t = cos_i / c_crit (the refracted horizon
// meets the critical angle, c_t = c_crit = cos_i / cos t) and cos t = cos_i / (2 c_crit) (the reflected one does),
// where that falls inside [0, pi]. The first piece is in r = tan t = r0 sinh y (the slope law's core at any
// roughness), y = Y u (2 - u) flat at its upper end; the others in t = smoothstep, S(u) = u^2 (3 - 2u), flat at both.

// The incidence (mu = cos_i in (0, 1]) and the interface of relative index eta (below over above) that every (t, c)
// of dielectric_albedos_at shares.
struct DielectricSetting {
    FunctionRef Lambda;
    G2Form form;
    double eta, ci, si, ti, Li;
    bool tir;  // eta < 1: total internal reflection below the critical angle c_crit = sqrt(1 - eta^2)
    double c_crit, eta2m1, r0;
    bool core;  // the core slope scale r0 = 1 / sqrt(pi P22(0)) finite and > 0; else the first piece in t, no layers
};

DielectricSetting dielectric_setting(FunctionRef P22, FunctionRef Lambda, double mu, double eta, G2Form form) {
    const double ci = mu, si = std::sqrt((1.0 - mu) * (1.0 + mu)), ti = std::acos(mu);
    const double Li = si > 0.0 ? Lambda(ci / si) : 0.0;
    const bool tir = eta < 1.0;
    const double c_crit = tir ? std::sqrt((1.0 - eta) * (1.0 + eta)) : 0.0;
    const double eta2m1 = (eta - 1.0) * (eta + 1.0);
    const double r0 = 1.0 / std::sqrt(pi * P22(0.0));
    return {Lambda, form, eta, ci, si, ti, Li, tir, c_crit, eta2m1, r0, r0 > 0.0 && r0 < INFINITY};
}

// The integrand at (t, c) without the measure: (c / cos t) {F G2_R above wr's horizon, (1 - F) G2_T below wt's},
// mz = cos t.
Albedos dielectric_facet(const DielectricSetting& d, double mz, double c) {
    if (!(c > 0.0)) return {};
    Albedos v;
    const double a = c / mz, wrz = 2.0 * c * mz - d.ci, g2 = d.eta2m1 + c * c;
    if (!(g2 > 0.0)) {  // total internal reflection
        if (wrz > 0.0) v.R = a * G2_from_Lambdas(d.Li, Lambda_of_z(d.Lambda, wrz), true, d.form);
        return v;
    }
    // Walter eq. 22 (fresnel_dielectric's), with g = eta cos theta_t shared with wt (eq. 40).
    const double g = std::sqrt(g2), A = (g - c) / (g + c), B = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    const double F = 0.5 * A * A * (1.0 + B * B);
    if (wrz > 0.0) v.R = a * F * G2_from_Lambdas(d.Li, Lambda_of_z(d.Lambda, wrz), true, d.form);
    const double wtz = ((c - g) * mz - d.ci) / d.eta;
    if (wtz < 0.0 && F < 1.0) v.T = a * (1.0 - F) * G2_across(d.Li, Lambda_of_z(d.Lambda, wtz), d.form);
    return v;
}

// The normals at one inclination t (mz = cos t): c = wi.m over [c_min, c_max] = [c0 - s, c0 + s]; the w axis's D =
// c_max - c_crit, its square root and the w of c_min (0 unless c_min is above the critical angle).
struct NormalRing {
    double mz, s, c0, c_max, c_min, D, sD, w_min;
};

NormalRing normal_ring(const DielectricSetting& d, double mz, double st) {
    const double s = d.si * st, c0 = d.ci * mz, c_max = c0 + s, c_min = c0 - s;
    const double D = c_max - d.c_crit, sD = std::sqrt(std::max(D, 0.0));
    const double w_min = d.tir && c_min > d.c_crit ? std::asin(std::sqrt((c_min - d.c_crit) / D)) : 0.0;
    return {mz, s, c0, c_max, c_min, D, sD, w_min};
}

enum class BreakKind { end, reflected, critical, refracted, other };
struct RingBreak {
    double c;
    BreakKind kind;
};
// A ring's break points in c, descending from c_max to c_min, and the least c where the integrand lives.
struct RingBreaks {
    std::array<RingBreak, 12> at;
    int n = 0;
    double support = 0.0;
};

// The break points in c listed above, at one ring.
RingBreaks ring_breaks(const DielectricSetting& d, const NormalRing& g) {
    RingBreaks b;
    b.at[b.n++] = {g.c_max, BreakKind::end};
    auto add = [&](double c, BreakKind kind) {
        if (c > g.c_min && c < g.c_max) b.at[b.n++] = {c, kind};
    };
    const double mz = g.mz, ci = d.ci, r0 = d.r0, c_refl = ci / (2.0 * mz);
    add(c_refl, BreakKind::reflected);
    const double wrz_top = 2.0 * g.c_max * mz - ci;
    for (double k : {1.0, 4.0, 16.0})
        if (d.core && k * r0 < 0.2 && k * r0 < 0.25 * wrz_top) add((ci + k * r0) / (2.0 * mz), BreakKind::other);
    b.support = c_refl;  // no integrand below
    if (d.tir) {
        add(d.c_crit, BreakKind::critical);
        b.support = std::min(b.support, d.c_crit);
        const double c_t = (ci * ci + mz * mz * (1.0 - d.eta) * (1.0 + d.eta)) / (2.0 * mz * ci);
        if (c_t * mz >= ci && c_t >= d.c_crit && c_t < g.c_max) {
            add(c_t, BreakKind::refracted);
            const double wtz_bottom = -((g.c_max - std::sqrt(d.eta2m1 + g.c_max * g.c_max)) * mz - ci) / d.eta;
            for (double k : {1.0, 4.0, 16.0}) {
                // wt.z = -z: c - g = A = (cos_i - eta z) / cos t, c = (A^2 + c_crit^2) / (2 A)
                const double z = k * r0, A = (ci - d.eta * z) / mz;
                if (d.core && z < 0.2 && z < 0.25 * wtz_bottom && A > 0.0)
                    add((A * A + d.c_crit * d.c_crit) / (2.0 * A), BreakKind::other);
            }
        }
    } else {
        add(0.0, BreakKind::other);
        b.support = 0.0;
    }
    b.at[b.n++] = {g.c_min, BreakKind::end};
    std::sort(b.at.begin(), b.at.begin() + b.n, [](const RingBreak& x, const RingBreak& y) { return x.c > y.c; });
    return b;
}

// One piece of a ring's inner integral between two break points.
struct RingPiece {
    bool in_w;       // w (c = c_crit + D sin^2 w, u = 0 at the lower c), else phi (u = 0 at phi's lower end)
    int flat;        // 1: flat at u = 0, 2: at u = 1, 3: both
    double lo, len;  // of w or phi
    bool to_min;     // a w piece down to c0 - s (phi = pi)
};
struct RingPieces {
    std::array<RingPiece, 11> at;
    int n = 0;
};

// The pieces between the ring's break points where the integrand lives: in w above the critical angle, else in phi.
RingPieces ring_pieces(const DielectricSetting& d, const NormalRing& g, const RingBreaks& b) {
    auto w_of = [&](double c) { return std::asin(std::min(1.0, std::sqrt((c - d.c_crit) / g.D))); };
    RingPieces p;
    for (int i = 0; i + 1 < b.n; ++i) {
        const RingBreak &hi = b.at[i], &lo = b.at[i + 1];
        if (!(hi.c > lo.c) || !(hi.c > b.support)) continue;
        if (d.tir && lo.c >= d.c_crit) {
            const double wa = lo.kind == BreakKind::end ? g.w_min : lo.kind == BreakKind::critical ? 0.0 : w_of(lo.c);
            const double wb = hi.kind == BreakKind::end ? pi / 2 : w_of(hi.c);
            const int flat = (lo.kind == BreakKind::end || lo.kind == BreakKind::refracted ? 1 : 0) +
                (hi.kind == BreakKind::refracted ? 2 : 0);
            p.at[p.n++] = {true, flat, wa, wb - wa, lo.kind == BreakKind::end};
        } else {
            const double pa = hi.kind == BreakKind::end ? 0.0 : std::acos(std::clamp((hi.c - g.c0) / g.s, -1.0, 1.0));
            const double pb = lo.kind == BreakKind::end ? pi : std::acos(std::clamp((lo.c - g.c0) / g.s, -1.0, 1.0));
            const int flat = (hi.kind == BreakKind::refracted ? 1 : 0) + (lo.kind == BreakKind::refracted ? 2 : 0);
            p.at[p.n++] = {false, flat, pa, pb - pa, false};
        }
    }
    return p;
}

// The inner integrand at x in [0, n): piece i = int(x) at u = x - i, through its map and Jacobian.
Albedos piece_albedos(const DielectricSetting& d, const NormalRing& g, const RingPieces& pieces, double x) {
    const int i = std::min(static_cast<int>(x), pieces.n - 1);
    const RingPiece& p = pieces.at[i];
    const double u = x - i, q = 1.0 - u;
    double S = u, dS = 1.0;  // the map [0, 1] -> [0, 1] and its derivative
    if (p.flat == 1) S = u * u, dS = 2.0 * u;
    if (p.flat == 2) S = u * (1.0 + q), dS = 2.0 * q;
    if (p.flat == 3) S = u * u * (3.0 - 2.0 * u), dS = 6.0 * u * q;
    if (!p.in_w) {
        const Albedos y = dielectric_facet(d, g.mz, g.c0 + g.s * std::cos(p.lo + p.len * S));
        return {y.R * dS * p.len, y.T * dS * p.len};
    }
    const double w = p.lo + p.len * S, sw = std::sin(w), c = d.c_crit + g.D * sw * sw;
    // c - (c0 - s) = D (sin^2 w - sin^2 w_min) without cancellation at w_min
    const double above_min = p.to_min ? g.D * std::sin(p.len * S) * std::sin(w + g.w_min) : c - g.c_min;
    if (!(above_min > 0.0)) return {};
    const Albedos y = dielectric_facet(d, g.mz, c);
    const double j = dS * p.len * 2.0 * g.sD * sw / std::sqrt(above_min);
    return {y.R * j, y.T * j};
}

// The inner integral at inclination t, times its measure P22 tan t / cos^2 t.
Albedos ring_albedos(const DielectricSetting& d, FunctionRef P22, double t, double inner_tol) {
    if (!(t < pi / 2)) return {};
    const double mz = std::cos(t), st = std::sin(t), r = st / mz;
    const double measure = r * P22(r * r) / (mz * mz);
    if (!(measure > 0.0)) return {};
    const NormalRing g = normal_ring(d, mz, st);
    if (!(g.s > 0.0)) {
        const Albedos y = dielectric_facet(d, mz, g.c0);
        return {measure * pi * y.R, measure * pi * y.T};
    }
    const RingPieces pieces = ring_pieces(d, g, ring_breaks(d, g));
    if (pieces.n == 0) return {};
    const Albedos sum =
        adapt([&](double x) -> Albedos { return piece_albedos(d, g, pieces, x); }, pieces.n, inner_tol, 200);
    return {measure * sum.R, measure * sum.T};
}

// The outer integral's break points in t listed above, ascending from 0 to pi/2.
std::vector<double> inclination_breaks(const DielectricSetting& d) {
    const double ci = d.ci, si = d.si, ti = d.ti, eta = d.eta, c_crit = d.c_crit;
    std::vector<double> tb{0.0, pi / 2};
    auto add_t = [&](double t) {
        if (t > 0.0 && t < pi / 2) tb.push_back(t);
    };
    add_t(pi / 4 - ti / 2);
    add_t(pi / 4 + ti / 2);
    if (d.tir) {
        const double tc = std::acos(c_crit);
        add_t(ti + tc);
        add_t(std::abs(tc - ti));
        for (double a : {si, -si})
            for (double b : {eta, -eta}) {
                const double T = (a + b) / ci;
                if (!(T > 0.0)) continue;
                const double t = std::atan(T), mz = std::cos(t);
                const double c_t = (ci * ci + mz * mz * (1.0 - eta) * (1.0 + eta)) / (2.0 * mz * ci);
                if (c_t * mz >= ci * (1.0 - 1e-12) && c_t >= c_crit * (1.0 - 1e-12)) add_t(t);
            }
        auto inside = [&](double t) { return std::cos(t + ti) <= c_crit && c_crit <= std::cos(t - ti); };
        for (double cz : {ci / c_crit, ci / (2.0 * c_crit)})
            if (cz < 1.0 && inside(std::acos(cz))) add_t(std::acos(cz));
    } else {
        add_t(pi / 2 - ti);
    }
    std::sort(tb.begin(), tb.end());
    tb.erase(std::unique(tb.begin(), tb.end()), tb.end());
    return tb;
}

// E_R and E_T: the outer integral over the pieces in t, each the inner integral of its ring.
Albedos dielectric_albedos_at(FunctionRef P22, FunctionRef Lambda, double mu, double tolerance, double eta,
                              G2Form form) {
    const DielectricSetting d = dielectric_setting(P22, Lambda, mu, eta, form);
    const std::vector<double> tb = inclination_breaks(d);
    const int pieces = static_cast<int>(tb.size()) - 1;
    const double Y = d.core ? std::asinh(std::tan(tb[1]) / d.r0) : 0.0, inner_tol = 0.1 * tolerance;
    const Albedos sum = adapt(
        [&](double x) -> Albedos {
            const int i = std::min(static_cast<int>(x), pieces - 1);
            const double u = x - i;
            double t, dt;
            if (i == 0 && d.core) {  // r = r0 sinh y, y = Y u (2 - u)
                const double y = Y * u * (2.0 - u), r = d.r0 * std::sinh(y);
                t = std::atan(r), dt = Y * 2.0 * (1.0 - u) * d.r0 * std::cosh(y) / (1.0 + r * r);
            } else {
                const double L = tb[i + 1] - tb[i];
                t = tb[i] + L * u * u * (3.0 - 2.0 * u), dt = L * 6.0 * u * (1.0 - u);
            }
            const Albedos y = ring_albedos(d, P22, t, inner_tol);
            return {y.R * dt, y.T * dt};
        },
        pieces, tolerance, 400);
    return {2.0 * sum.R / d.ci, 2.0 * sum.T / d.ci};
}

// 2 integral_0^1 g(mu) mu dmu in x, the table's warped cosine at alpha, cell by cell (8-point Gauss-Legendre a cell):
// the lookup is linear in x there, and mu(x) = c x^2 / (1 + c - x^2) rational (c the warp's scale at alpha), with
// dmu/dx = 2 c (1 + c) x / (1 + c - x^2)^2 (in mu the first cell goes like sqrt(mu)). g is given mu clamped to 1.
template <class G>
double cosine_integral(const AlbedoTable& E, double alpha, const G& g) {
    // 8-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz and Stegun, table 25.4).
    static constexpr double x8[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static constexpr double w8[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    if (E.grid.cluster.weight != 0.0)
        throw input_error("the cosine integral of a table: its axis has a node cluster (only the warp is integrated)");
    const double c = E.grid.scale(alpha), k = 1.0 + c;
    double integral = 0.0;
    for (int j = 0; j + 1 < E.grid.n_x; ++j) {
        const double a = E.grid.x(j), b = E.grid.x(j + 1), mid = 0.5 * (a + b), half = 0.5 * (b - a);
        for (int q = 0; q < 4; ++q)
            for (double sgn : {-1.0, 1.0}) {
                const double x = mid + sgn * half * x8[q], d = k - x * x;
                const double mu = c * x * x / d, dmu = 2.0 * c * k * x / (d * d);
                integral += w8[q] * half * g(std::min(mu, 1.0)) * mu * dmu;
            }
    }
    return 2.0 * integral;
}

}  // namespace

namespace detail {

double single_scattering_albedo(FunctionRef P22, FunctionRef Lambda, const FunctionRef* F, double mu, double tolerance,
                                G2Form form, double slope_scale) {
    require(mu >= 0.0 && mu <= 1.0, "mu = cos(theta_i)", "in [0, 1]", mu);
    if (mu > 0.0) return reflection_albedo(P22, Lambda, F, mu, tolerance, form, slope_scale);
    if (!F && form == G2Form::height_correlated) return 1.0;
    return grazing_albedo(P22, Lambda, F, {false, 1.0, form}, tolerance);
}

std::pair<double, double> dielectric_albedos(FunctionRef P22, FunctionRef Lambda, double mu, double tolerance,
                                             double eta, G2Form form) {
    require(mu >= 0.0 && mu <= 1.0, "mu = cos(theta_i)", "in [0, 1]", mu);
    require(eta > 0.0 && std::isfinite(eta), "eta", "finite and > 0", eta);
    if (mu == 0.0) {
        auto Fd = [eta](double c) { return fresnel_dielectric(c, eta); };
        const FunctionRef F(Fd);
        return {grazing_albedo(P22, Lambda, &F, {false, eta, form}, tolerance),
                grazing_albedo(P22, Lambda, nullptr, {true, eta, form}, tolerance)};
    }
    const Albedos a = dielectric_albedos_at(P22, Lambda, mu, tolerance, eta, form);
    return {a.R, a.T};
}

double cosine_average(FunctionRef e, double tolerance) {
    return 2.0 * integrate([&](double mu) { return e(mu) * mu; }, 0.0, 1.0, {Backend::boost, tolerance});
}

}  // namespace detail

double compensation_lobe(const AlbedoTable& E, const std::vector<double>& missing, double alpha, double mu_i,
                         double mu_o) {
    const double m = lookup_missing(E.grid.alphas, missing, alpha);
    return (1.0 - E.lookup(alpha, mu_i)) * (1.0 - E.lookup(alpha, mu_o)) / (pi * m);
}

NodeCluster dielectric_cluster(double eta, double alpha_min) {
    require(eta > 0.0 && std::isfinite(eta), "eta", "finite and > 0", eta);
    require(alpha_min > 0.0 && std::isfinite(alpha_min), "the grid's first alpha", "finite and > 0", alpha_min);
    if (eta >= 1.0) return {};
    // sin(theta_c) = eta: the kink's width in mu at alpha is ~ alpha eta.
    return {std::sqrt((1.0 - eta) * (1.0 + eta)), 2.0 * alpha_min * eta, 0.35};
}

AlbedoGrid dielectric_grid(const AlbedoGrid& E, int n_x, double eta) {
    E.check();
    AlbedoGrid g{E.alphas, E.scales, n_x, dielectric_cluster(eta, E.alphas.front())};
    g.check();
    return g;
}

double fresnel_ms(double F_avg, double E_avg) { return F_avg * F_avg * E_avg / (1.0 - F_avg * (1.0 - E_avg)); }

double table_missing(const AlbedoTable& E, double alpha) {
    return cosine_integral(E, alpha, [&](double mu) { return 1.0 - E.lookup(alpha, mu); });
}

std::vector<double> table_missing(const AlbedoTable& E) {
    std::vector<double> m;
    for (double alpha : E.grid.alphas) m.push_back(table_missing(E, alpha));
    return m;
}

namespace {

// The table's own 1 - E_avg at alpha over m, the 1 - E_avg the lobe is divided by.
double ratio_to(const AlbedoTable& E, double alpha, double m) { return table_missing(E, alpha) / m; }

}  // namespace

double kulla_conty_ratio(const AlbedoTable& E, const std::vector<double>& missing, double alpha) {
    return ratio_to(E, alpha, lookup_missing(E.grid.alphas, missing, alpha));
}

double kulla_conty_albedo(const AlbedoTable& E, const std::vector<double>& missing, double alpha, double mu_i,
                          double F_avg) {
    require(F_avg >= 0.0 && F_avg <= 1.0, "F_avg", "in [0, 1]", F_avg);
    const double m = lookup_missing(E.grid.alphas, missing, alpha);
    // pi times the lobe's cosine integral over wo: (1 - E(mu_i)) times 2 integral (1 - E(mu)) mu dmu / m.
    return fresnel_ms(F_avg, 1.0 - m) * (1.0 - E.lookup(alpha, mu_i)) * ratio_to(E, alpha, m);
}

double fdez_aguera_albedo(double E_F, double E, double F_avg) {
    require(E > 0.0, "E(mu)", "> 0", E);
    require(F_avg >= 0.0 && F_avg <= 1.0, "F_avg", "in [0, 1]", F_avg);
    return E_F / (1.0 - F_avg * (1.0 - E));
}

double turquin_scale(double E_view, double F0) {
    require(E_view > 0.0, "E(mu_view)", "> 0", E_view);
    return 1.0 + F0 * (1.0 - E_view) / E_view;
}

std::string compensation_header_name(std::string_view family_name) {
    std::string id = "smithlab_";
    bool sep = false;
    for (char c : family_name) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        if (ok) {
            if (sep && id.back() != '_') id += '_';
            id += c;
            sep = false;
        } else {
            sep = true;
        }
    }
    while (!id.empty() && id.back() == '_') id.pop_back();
    return id;
}

}  // namespace smithlab::compensation
