// The diffuse models (fit/diffuse_models.hpp has each formula and its source).
//
// Symmetry in wi and wo is kept to the last bit wherever it is cheap: every quantity is built from symmetric pieces
// (wi.wo, wi + wo, min and max of the two cosines, the products of the two Schlick factors), so f(wi, wo) and
// f(wo, wi) differ at most by the rounding of a product's order.
#include "smithlab/fit/diffuse_models.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "smithlab/errors.hpp"

namespace smithlab::fit {

namespace {

using std::numbers::pi;
constexpr double inv_pi = std::numbers::inv_pi;

double pow5(double x) {
    const double x2 = x * x;
    return x2 * x2 * x;
}

// s = wi.wo - (n.wi)(n.wo) = cos(phi) sin(theta_i) sin(theta_o), from the tangential components: no cancellation.
double tangential_dot(const Vec3& wi, const Vec3& wo) { return wi.x() * wo.x() + wi.y() * wo.y(); }

// Fujii's s/t (and EON's): s where s <= 0, else s / max(n.wi, n.wo) (= cos(phi) sin(alpha') tan(beta)).
double s_over_t(const Vec3& wi, const Vec3& wo) {
    const double s = tangential_dot(wi, wo);
    return s > 0.0 ? s / std::max(wi.z(), wo.z()) : s;
}

// EON's constants (the paper's constant1_FON and constant2_FON): A = 1/(1 + c1 r), <E_F> = A (1 + c2 r).
constexpr double eon_c1 = 0.5 - 2.0 / (3.0 * pi);
constexpr double eon_c2 = 2.0 / 3.0 - 28.0 / (15.0 * pi);

// G(mu) of E_F (see eon_fon_albedo), with (S/mu)(1 - S^3) = S mu (1 + S + S^2)/(1 + S) (as 1 - S = mu^2/(1 + S)):
// no 0/0 at grazing, where G -> pi/2 - 2/3 = pi c1.
double eon_g(double mu) {
    const double m = std::clamp(mu, 0.0, 1.0), s = std::sqrt((1.0 - m) * (1.0 + m));
    return s * (std::acos(m) - s * m) + (2.0 / 3.0) * (s * m * (1.0 + s + s * s) / (1.0 + s) - s);
}
// 1 - E_F(mu) = A r (c1 - G(mu)/pi), written without the cancellation of 1 - E_F near r = 0 and near grazing.
double eon_one_minus_fon_albedo(double mu, double r) {
    return r / (1.0 + eon_c1 * r) * std::max(0.0, eon_c1 - eon_g(mu) * inv_pi);
}
// rho_ms = rho^2 <E_F> / (1 - rho (1 - <E_F>)).
double eon_rho_ms(double r, double albedo) {
    const double avg = eon_fon_average_albedo(r);
    return albedo * albedo * avg / (1.0 - albedo * (1.0 - avg));
}

}  // namespace

double lambert(double albedo) { return albedo * inv_pi; }

double disney_diffuse(const Vec3& wi, const Vec3& wo, double perceptual_roughness, double albedo) {
    // cos^2(theta_d) = (wi.h)^2 = |wi + wo|^2 / 4 (h = (wi + wo)/|wi + wo|).
    const double cos2_d = 0.25 * (wi + wo).squaredNorm();
    const double fd90_minus_1 = 2.0 * perceptual_roughness * cos2_d - 0.5;
    const double fl = 1.0 + fd90_minus_1 * pow5(1.0 - wi.z()), fv = 1.0 + fd90_minus_1 * pow5(1.0 - wo.z());
    return albedo * inv_pi * (fl * fv);
}

double oren_nayar(const Vec3& wi, const Vec3& wo, double sigma, double albedo) {
    const double s2 = sigma * sigma;
    const double ri = norm_xy(wi), ro = norm_xy(wo);
    // alpha' = max(theta_i, theta_o) and beta = min, by their sines and cosines (min and max keep it symmetric to the
    // bit): sin(alpha') = the larger sine, cos(beta) = the larger cosine. tan(beta) = sin/cos and
    // tan((alpha' + beta)/2) = (sin(alpha') + sin(beta)) / (cos(alpha') + cos(beta)) come from them directly: finite
    // for z > 0 and exact at grazing, where tan of an angle near pi/2 would lose digits.
    const double sin_a = std::max(ri, ro), sin_b = std::min(ri, ro);
    const double cos_a = std::min(wi.z(), wo.z()), cos_b = std::max(wi.z(), wo.z());
    const double a = std::atan2(sin_a, cos_a), b = std::atan2(sin_b, cos_b);
    const double tan_b = sin_b / cos_b, tan_half_sum = (sin_a + sin_b) / (cos_a + cos_b);
    // cos(phi): either direction along the normal makes it undefined, and every term it multiplies vanishes there
    // (tan(beta) = 0, beta = 0): 0 is as good as any value.
    const double rr = ri * ro;
    const double cos_phi = rr > 0.0 ? std::clamp(tangential_dot(wi, wo) / rr, -1.0, 1.0) : 0.0;
    const double b2 = 2.0 * b / pi;  // 2 beta / pi
    const double c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    const double c2 = 0.45 * s2 / (s2 + 0.09) * (cos_phi >= 0.0 ? sin_a : sin_a - b2 * b2 * b2);
    const double c3_root = 4.0 * a * b / (pi * pi), c3 = 0.125 * s2 / (s2 + 0.09) * c3_root * c3_root;
    const double l1 = c1 + cos_phi * c2 * tan_b + (1.0 - std::abs(cos_phi)) * c3 * tan_half_sum;
    const double l2 = 0.17 * albedo * s2 / (s2 + 0.13) * (1.0 - cos_phi * b2 * b2);
    return std::max(0.0, albedo * inv_pi * (l1 + l2));
}

double oren_nayar_qualitative(const Vec3& wi, const Vec3& wo, double sigma, double albedo) {
    const double s2 = sigma * sigma;
    const double a = 1.0 - 0.5 * s2 / (s2 + 0.33), b = 0.45 * s2 / (s2 + 0.09);
    // max(0, cos(phi)) sin(alpha') tan(beta) = max(0, s) / max(n.wi, n.wo): cos(beta) = max of the cosines.
    const double s = std::max(0.0, tangential_dot(wi, wo));
    return albedo * inv_pi * (a + b * (s / std::max(wi.z(), wo.z())));
}

double fujii(const Vec3& wi, const Vec3& wo, double sigma, double albedo) {
    const double a = 1.0 / (1.0 + eon_c1 * sigma), b = sigma * a;
    return std::max(0.0, albedo * inv_pi * (a + b * s_over_t(wi, wo)));
}

double eon_fon_albedo(double mu, double r) {
    const double a = 1.0 / (1.0 + eon_c1 * r);
    return a * (1.0 + r * eon_g(mu) * inv_pi);
}

double eon_fon_average_albedo(double r) { return (1.0 + eon_c2 * r) / (1.0 + eon_c1 * r); }

double eon_albedo(double mu, double r, double albedo) {
    return albedo * eon_fon_albedo(mu, r) + eon_rho_ms(r, albedo) * eon_one_minus_fon_albedo(mu, r);
}

double eon(const Vec3& wi, const Vec3& wo, double r, double albedo) {
    const double a = 1.0 / (1.0 + eon_c1 * r);
    const double f_ss = albedo * inv_pi * a * (1.0 + r * s_over_t(wi, wo));
    // f_ms = rho_ms/pi (1 - E_F(mu_i))(1 - E_F(mu_o)) / (1 - <E_F>), with 1 - <E_F> = A r (c1 - c2): one factor
    // A r cancels, no 0/0 at r = 0.
    const double one_minus_i = std::max(0.0, eon_c1 - eon_g(wi.z()) * inv_pi);
    const double one_minus_o = std::max(0.0, eon_c1 - eon_g(wo.z()) * inv_pi);
    const double f_ms = eon_rho_ms(r, albedo) * inv_pi * (a * r) * (one_minus_i * one_minus_o) / (eon_c1 - eon_c2);
    return std::max(0.0, f_ss) + f_ms;
}

double chan_2018(const Vec3& wi, const Vec3& wo, double alpha, double albedo, double retro_weight) {
    const Vec3 sum = wi + wo;
    const double len = sum.norm();
    const double voh = std::clamp(0.5 * len, 0.0, 1.0);                // V.H = |L + V| / 2
    const double noh = std::clamp((wi.z() + wo.z()) / len, 0.0, 1.0);  // N.H = (N.L + N.V) / |L + V|
    const double nol = std::clamp(wi.z(), 0.0, 1.0), nov = std::clamp(wo.z(), 0.0, 1.0);
    // a2 = 2 / (1 + 2^(18 g)) inverted; 2/a2 - 1 kept positive so that alpha > sqrt(2) reads as g = 0, not NaN.
    const double a2 = alpha * alpha;
    const double g = std::clamp(std::log2(std::max(2.0 / a2 - 1.0, 1e-300)) / 18.0, 0.0, 1.0);
    const double f0 = voh + pow5(1.0 - voh);
    const double fdv = 1.0 - 0.75 * pow5(1.0 - nov), fdl = 1.0 - 0.75 * pow5(1.0 - nol);
    const double t = std::clamp(2.2 * g - 0.5, 0.0, 1.0);
    const double fd = f0 + t * (fdv * fdl - f0);
    const double fb =
        ((34.5 * g - 59.0) * g + 24.5) * voh * std::exp2(-std::max(73.2 * g - 21.2, 8.9) * std::sqrt(noh));
    return albedo * inv_pi * (fd + retro_weight * fb);
}

double hammon_2017_single(const Vec3& wi, const Vec3& wo, double alpha, const HammonConstants& k) {
    const Vec3 sum = wi + wo;
    const double len2 = sum.squaredNorm();
    const double facing = 0.25 * len2;                       // 0.5 + 0.5 L.V = |L + V|^2 / 4 (the slide's identity)
    const double noh = (wi.z() + wo.z()) / std::sqrt(len2);  // N.H = (N.L + N.V) / |L + V|, > 0 for z > 0
    const double rough = facing * (k.rough_a - k.rough_b * facing) * ((k.rough_c + noh) / noh);
    const double smooth = k.smooth * ((1.0 - pow5(1.0 - wi.z())) * (1.0 - pow5(1.0 - wo.z())));
    return inv_pi * (smooth + alpha * (rough - smooth));
}

double hammon_2017(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const HammonConstants& k) {
    return albedo * (hammon_2017_single(wi, wo, alpha, k) + albedo * (k.multi * alpha));
}

double hammon_2017_linear(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const HammonConstants& k) {
    return albedo * (hammon_2017_single(wi, wo, alpha, k) + k.multi * alpha);
}

double smithlab_2026(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const Smithlab2026Constants& k) {
    const double t = std::pow(alpha, k.p);
    const double facing = 0.25 * (wi + wo).squaredNorm();
    const double multi = k.hammon.multi * std::pow(alpha, k.q) * (1.0 + k.u * (1.0 - facing));
    return albedo * (hammon_2017_single(wi, wo, t, k.hammon) + albedo * multi);
}

// ---- the table ----------------------------------------------------------------------------------------------------

namespace {

constexpr double inf = INFINITY;

// The ranges of Hammon 2017's constants (his slide's terms): the rough term's shape a - b facing is left free; the
// others are non-negative where the term they scale is.
std::vector<ParameterRange> hammon_ranges() {
    return {{},
            {},
            {0.0, inf, "rough = facing (a - b facing)(c + N.H)/N.H: below c = 0 it changes sign toward grazing N.H"},
            {0.0, inf, "smooth = k (1 - (1 - N.L)^5)(1 - (1 - N.V)^5): negative light below k = 0"},
            {0.0, inf, "multi = m alpha, the light scattered more than once: negative below m = 0"}};
}

std::vector<ParameterRange> smithlab_2026_ranges() {
    std::vector<ParameterRange> r = hammon_ranges();
    r.push_back({0.0, inf, "the roughness blend alpha^p: at p <= 0 it does not vanish as alpha -> 0"});
    r.push_back({0.0, inf, "multi = m alpha^q: at q <= 0 it does not vanish as alpha -> 0"});
    r.push_back({-1.0, inf, "1 + u (1 - facing), facing in [0, 1]: negative below u = -1"});
    return r;
}

HammonConstants hammon_constants(const double* c) { return {c[0], c[1], c[2], c[3], c[4]}; }

double f_lambert(const Vec3&, const Vec3&, double, double albedo, const double*) { return lambert(albedo); }
double f_disney(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double*) {
    return disney_diffuse(wi, wo, std::sqrt(alpha), albedo);
}
double f_oren_nayar(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c) {
    return oren_nayar(wi, wo, c[0] * alpha, albedo);
}
double f_oren_nayar_sqrt2(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double*) {
    return oren_nayar(wi, wo, alpha * std::numbers::sqrt2 * 0.5, albedo);
}
double f_oren_nayar_qualitative(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double*) {
    return oren_nayar_qualitative(wi, wo, 0.5 * alpha, albedo);
}
double f_fujii(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c) {
    return fujii(wi, wo, c[0] * alpha, albedo);
}
double f_eon(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c) {
    return eon(wi, wo, std::clamp(c[0] * alpha, 0.0, 1.0), albedo);
}
double f_chan(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double*) {
    return chan_2018(wi, wo, alpha, albedo, 1.0);
}
double f_hammon(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c) {
    return hammon_2017(wi, wo, alpha, albedo, hammon_constants(c));
}
double f_hammon_linear(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c) {
    return hammon_2017_linear(wi, wo, alpha, albedo, hammon_constants(c));
}
double f_smithlab_2026(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c) {
    return smithlab_2026(wi, wo, alpha, albedo, {hammon_constants(c), c[5], c[6], c[7]});
}

}  // namespace

const std::vector<DiffuseModel>& diffuse_models() {
    static const std::vector<DiffuseModel> models{
        {"lambert", {}, {}, "Lambert 1760, Photometria: albedo/pi", f_lambert},
        {"disney", {}, {}, "Burley 2012, Physically-Based Shading at Disney, sec. 5.3 (r = sqrt(alpha))", f_disney},
        {"oren-nayar",
         {"sigma_scale"},
         {0.5},
         "Oren & Nayar 1994, Generalization of Lambert's Reflectance Model, full model with L2; sigma = s alpha, "
         "s = 0.5 as in Hammon 2017's comparison",
         f_oren_nayar,
         true,
         {{0.0, std::numbers::pi / 2.0,
           "sigma = s alpha, the standard deviation of the facets' slope angle (Oren & Nayar 1994 sec. 3), an angle "
           "within (-pi/2, pi/2): at most pi/2 at alpha = 1"}}},
        {"oren-nayar-sqrt2",
         {},
         {},
         "Oren & Nayar 1994, Generalization of Lambert's Reflectance Model, full model with L2; sigma = alpha/sqrt(2)",
         f_oren_nayar_sqrt2},
        {"oren-nayar-qualitative",
         {},
         {},
         "Oren & Nayar 1994, Generalization of Lambert's Reflectance Model, qualitative model; sigma = 0.5 alpha",
         f_oren_nayar_qualitative},
        {"fujii",
         {"sigma_scale"},
         {1.0},
         "Fujii 2013, A tiny improvement of Oren-Nayar reflectance model; sigma = s alpha, start s = 1 (not published)",
         f_fujii,
         true,
         {{0.0, 1.0,
           "sigma = s alpha: above sigma = 1 Fujii's f turns negative (A + B s >= A (1 - sigma)), held at 0 here"}}},
        {"eon",
         {"r_scale"},
         {1.0},
         "Portsmouth, Kutz & Hill 2025, EON: A Practical Energy-Preserving Rough Diffuse BRDF, JCGT 14(1), "
         "exact E_FON; r = clamp(c alpha, 0, 1), start c = 1 (not published)",
         f_eon,
         true,
         {{0.0, 1.0,
           "r = clamp(c alpha, 0, 1): above c = 1 EON's roughness r (in [0, 1]) is held at 1 from alpha = 1/c on"}}},
        {"chan-2018",
         {},
         {},
         "Chan 2018, Material Advances in Call of Duty: WWII (SIGGRAPH course), as UE5 BRDF.ush Diffuse_Chan, a2 = "
         "alpha^2, retro-reflectivity weight 1",
         f_chan},
        {"hammon-2017",
         {"rough_a", "rough_b", "rough_c", "smooth", "multi"},
         {0.9, 0.4, 0.5, 1.05, 0.1159},
         "Hammon 2017, PBR Diffuse Lighting for GGX+Smith Microsurfaces (GDC), GGX Diffuse Approximation: "
         "albedo (single + albedo multi)",
         f_hammon,
         true,
         hammon_ranges()},
        {"hammon-2017-linear",
         {"rough_a", "rough_b", "rough_c", "smooth", "multi"},
         {0.9, 0.4, 0.5, 1.05, 0.1159},
         "Hammon 2017, PBR Diffuse Lighting for GGX+Smith Microsurfaces (GDC), GGX Diffuse Approximation: "
         "albedo (single + multi)",
         f_hammon_linear,
         true,
         hammon_ranges()},
        {"smithlab-2026",
         {"rough_a", "rough_b", "rough_c", "smooth", "multi", "blend_power", "multi_power", "multi_forward"},
         {0.9, 0.4, 0.5, 1.05, 0.1159, 1.0, 1.0, 0.0},
         "smithlab 2026 (this tool's own, from the traced data): Hammon 2017's single term blended by alpha^p, "
         "multi = m alpha^q (1 + u (1 - facing)); starts at Hammon's constants",
         f_smithlab_2026,
         false,
         smithlab_2026_ranges()},
    };
    return models;
}

const ParameterRange* outside_range(const DiffuseModel& m, std::size_t i, double value) {
    if (i >= m.ranges.size()) return nullptr;
    const ParameterRange& r = m.ranges[i];
    return r.lo < value && value < r.hi ? nullptr : &r;
}

const DiffuseModel& find_diffuse_model(std::string_view name) {
    const std::vector<DiffuseModel>& models = diffuse_models();
    for (const DiffuseModel& m : models)
        if (m.name == name) return m;
    std::string known;
    for (std::size_t i = 0; i < models.size(); ++i) {
        if (i > 0) known += ", ";
        known += models[i].name;
    }
    throw input_error("unknown diffuse model '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace smithlab::fit
