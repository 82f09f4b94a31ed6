#include "smithlab/variants.hpp"

#include <array>
#include <cmath>
#include <memory>
#include <utility>

#include "smithlab/errors.hpp"
#include "smithlab/lambda_table.hpp"

namespace smithlab {

void VariantRegistry::add(LambdaVariant v) {
    if (find(v.name)) throw input_error("Lambda variant '" + v.name + "' is already registered");
    variants_.push_back(std::move(v));
}

const LambdaVariant* VariantRegistry::find(std::string_view name) const {
    for (const auto& v : variants_)
        if (v.name == name) return &v;
    return nullptr;
}

const LambdaVariant& VariantRegistry::at(std::string_view name) const {
    if (const LambdaVariant* v = find(name)) return *v;
    throw input_error("unknown method '" + std::string(name) + "' (smithlab eval --list-methods lists them)");
}

LambdaRoute route_on(const LambdaVariant& variant, const AnyNdf& ndf) {
    if (variant.route != LambdaRoute::table) return variant.route;
    // tabulate_Lambda's exact route: else the fixed rule, Boost 1D where its estimate misses (so the reference is 2D)
    return ndf.has_closed_Lambda() ? LambdaRoute::closed : LambdaRoute::q1d_boost;
}

bool is_quadrature(LambdaRoute r) {
    return r == LambdaRoute::q1d_boost || r == LambdaRoute::q2d_boost || r == LambdaRoute::q1d_gsl ||
        r == LambdaRoute::q2d_gsl;
}

LambdaOfMu prepare(const LambdaVariant& variant, const AnyNdf& ndf, Downward downward) {
    if (!variant.applies(ndf))
        throw input_error(variant.refusal
                              ? variant.refusal(ndf)
                              : "method '" + variant.name + "' does not apply to a '" + ndf.family() + "' ndf");
    return [up = variant.prepare(ndf), downward](double mu) { return Lambda_at(mu, downward, up); };
}

double Lambda(const LambdaVariant& variant, const AnyNdf& ndf, double mu, Downward downward) {
    return prepare(variant, ndf, downward)(mu);
}

double Lambda_schlick_ggx(double alpha, double mu) { return alpha / (2.0 * mu * (mu + std::hypot(mu, 1.0))); }

double Lambda_beckmann_rational(double alpha, double mu) {
    const double a = mu / alpha;
    if (a >= 1.6) return 0.0;
    return (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}

namespace {

// The capabilities (ndf.hpp): the approximations made for GGX or Beckmann apply to whatever NDF is exactly one.
bool is_ggx_like(const AnyNdf& n) { return !std::isnan(ggx_alpha(n)); }
bool is_beckmann(const AnyNdf& n) { return !std::isnan(beckmann_alpha(n)); }

}  // namespace

double G2_hammon_lerp(double alpha, double mu_i, double mu_o) {
    const double nl = mu_i / std::hypot(mu_i, 1.0), nv = mu_o / std::hypot(mu_o, 1.0);
    const double a = 2.0 * nl * nv, b = nl + nv;
    return a / (a + alpha * (b - a));  // lerp(a, b, alpha) = a + alpha (b - a)
}

std::vector<G2Variant> builtin_G2_variants() {
    return {
        {"g2-uncorrelated", "exact G1(L) G1(V), Walter 2007 eq. 23: too small unless one Lambda is 0 (Hammon 2017)",
         [](const AnyNdf&) { return true; },
         [](const AnyNdf& n, double mi, double mo) { return G2(n, mi, mo, G2Form::uncorrelated); }},
        {"g2-schlick-uncorrelated", "Hammon 2017 / Unreal Schlick-style G1(L) G1(V) for GGX, k = alpha/2", is_ggx_like,
         [](const AnyNdf& n, double mi, double mo) {
             const double a = ggx_alpha(n);
             return 1.0 / ((1.0 + Lambda_schlick_ggx(a, mi)) * (1.0 + Lambda_schlick_ggx(a, mo)));
         }},
        {"g2-hammon-lerp",
         "Hammon 2017 height-correlated G2 approximation for GGX, 2 NL NV / lerp(2 NL NV, NL + NV, alpha)", is_ggx_like,
         [](const AnyNdf& n, double mi, double mo) { return G2_hammon_lerp(ggx_alpha(n), mi, mo); }},
    };
}

void register_core_variants(VariantRegistry& r) {
    struct Way {
        const char* name;
        Backend backend;
        LambdaRoute q1d, q2d;
    };
    const std::array<Way, 2> backends = {{{"boost", Backend::boost, LambdaRoute::q1d_boost, LambdaRoute::q2d_boost},
                                          {"gsl", Backend::gsl, LambdaRoute::q1d_gsl, LambdaRoute::q2d_gsl}}};
    const std::array<std::pair<const char*, double>, 5> tolerances = {
        {{"1e-4", 1e-4}, {"1e-6", 1e-6}, {"1e-8", 1e-8}, {"1e-10", 1e-10}, {"1e-12", 1e-12}}};
    auto any = [](const AnyNdf&) { return true; };
    for (const Way& way : backends)
        for (const auto& [tname, tol] : tolerances) {
            const QuadratureOptions q{way.backend, tol};
            r.add(
                {std::string("q1d-") + way.name + "-" + tname,
                 std::string("reduced 1D quadrature, ") +
                     (way.backend == Backend::boost ? "Boost tanh-sinh" : "GSL QAG") + ", relative tolerance " + tname,
                 any, [q](const AnyNdf& n) -> LambdaOfMu { return [n, q](double mu) { return Lambda_1d(n, mu, q); }; },
                 way.q1d});
            if (tol < 1e-8) continue;
            r.add(
                {std::string("q2d-") + way.name + "-" + tname,
                 std::string("nested 2D quadrature P22 -> P2 -> Lambda, ") + way.name + ", relative tolerance " + tname,
                 any, [q](const AnyNdf& n) -> LambdaOfMu { return [n, q](double mu) { return Lambda_2d(n, mu, q); }; },
                 way.q2d});
        }
    r.add({"closed-form", "the NDF's closed form (GGX, Beckmann, GTR at every integer gamma <= 31, Student-t)",
           [](const AnyNdf& n) { return n.has_closed_Lambda(); },
           [](const AnyNdf& n) -> LambdaOfMu { return [n](double mu) { return n.Lambda(mu); }; }, LambdaRoute::closed});
    r.add(
        {"table",
         "cubic spline of ln(mu Lambda) in ln mu, built per NDF from the exact route (est. relative 1e-6; ms to build)",
         any,
         [](const AnyNdf& n) -> LambdaOfMu {
             auto t = std::make_shared<const LambdaTable>(tabulate_Lambda(n));
             return [t](double mu) { return t->Lambda(mu); };
         },
         LambdaRoute::table});
    r.add({"schlick-ggx", "Hammon 2017 / Unreal Schlick-style G1 for GGX, k = alpha/2", is_ggx_like,
           [](const AnyNdf& n) -> LambdaOfMu {
               return [a = ggx_alpha(n)](double mu) { return Lambda_schlick_ggx(a, mu); };
           },
           LambdaRoute::other});
    r.add({"beckmann-rational", "Walter 2007 eq. 27 rational approximation of Beckmann G1", is_beckmann,
           [](const AnyNdf& n) -> LambdaOfMu {
               return [a = beckmann_alpha(n)](double mu) { return Lambda_beckmann_rational(a, mu); };
           },
           LambdaRoute::other});
}

}  // namespace smithlab
