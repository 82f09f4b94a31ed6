#include <string>

#include "smithlab/csv.hpp"
#include "smithlab/gtr/family.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/gtr/interpolants.hpp"
#include "smithlab/gtr/registry.hpp"
#include "smithlab/gtr/spline.hpp"

namespace smithlab {

void register_gtr_ndfs(NdfRegistry& r) {
    r.add(
        {"gtr",
         {"alpha", "gamma"},
         "Generalized Trowbridge-Reitz (Burley 2012), any real gamma >= 0; closed-form Lambda at integer gamma = 0.." +
             std::to_string(gtr_max_closed_gamma) + " (Dimov 2015 for 0..4, generated beyond), else by quadrature",
         {"gtr(alpha=1e-4, gamma=0.5)", "gtr(alpha=0.3, gamma=1)", "gtr(alpha=0.3, gamma=1.000000001)",
          "gtr(alpha=0.999999, gamma=1)", "gtr(alpha=1, gamma=3)", "gtr(alpha=0.2, gamma=0)",
          "gtr(alpha=0.5, gamma=2.5)", "gtr(alpha=0.05, gamma=4)", "gtr(alpha=0.05, gamma=10)"}},
        [](const NdfParams& p) { return gtr(p.at("alpha"), p.at("gamma")); });
}

namespace {

// Why the family evaluator does not take n: the parameter outside its domain, its value and the domain.
std::string gtr_family_refusal(const AnyNdf& n) {
    const std::string covers = "method 'family' covers gtr with alpha in [1e-4, 1] and gamma in [0, 20]; got ";
    if (n.family() != "gtr") return covers + "a '" + n.family() + "' ndf";
    const double a = n.param("alpha"), g = n.param("gamma");
    if (!GtrFamily::alpha_in_domain(a)) return covers + "alpha = " + format_shortest(a);
    return covers + "gamma = " + format_shortest(g);
}

}  // namespace

void register_gtr_variants(VariantRegistry& r) {
    auto is_gtr = [](const AnyNdf& n) { return n.family() == "gtr"; };
    r.add({"dimov-spline", "Dimov 2015 / V-Ray: natural cubic spline of G1 through gamma = 0..4, clamped above 4",
           is_gtr,
           [](const AnyNdf& n) -> LambdaOfMu {
               return [a = n.param("alpha"), g = n.param("gamma")](double mu) {
                   return Lambda_of_interpolated_G1(G1_gtr_dimov_spline(a, g, mu));
               };
           },
           LambdaRoute::other});
    // One evaluator for the whole family (family.hpp): no per-NDF work, alpha in [1e-4, 1], gamma in [0, 20].
    r.add(
        {"family",
         "compiled-in trees of polynomial patches over (alpha, gamma, mu), in two charts, for every GTR with alpha in "
         "[1e-4, 1], gamma in [0, 20], generated at build time (family.hpp)",
         [](const AnyNdf& n) {
             if (n.family() != "gtr") return false;
             const double a = n.param("alpha"), g = n.param("gamma");
             return GtrFamily::alpha_in_domain(a) && GtrFamily::gamma_in_domain(g);
         },
         [](const AnyNdf& n) -> LambdaOfMu {
             const double a = n.param("alpha"), g = n.param("gamma");
             require_gtr_family_domain(a, g);
             return [&t = GtrFamily::get(), a, g](double mu) { return t.Lambda_up(a, g, mu); };
         },
         LambdaRoute::other, gtr_family_refusal});
    using K = GammaInterpolant::Kind;
    using Q = GammaInterpolant::Quantity;
    const GammaInterpolant choices[] = {{K::akima, Q::G1, 4},
                                        {K::steffen, Q::G1, 4},
                                        {K::cspline, Q::Lambda, 4},
                                        {K::cspline, Q::log_Lambda, 4},
                                        {K::cspline, Q::log_Lambda, 10},
                                        {K::steffen, Q::log_Lambda, 10},
                                        {K::cspline, Q::log_Lambda, 20},
                                        {K::akima, Q::log_Lambda, 20}};
    for (const GammaInterpolant& how : choices)
        r.add({name_of(how), description_of(how), is_gtr,
               [how](const AnyNdf& n) -> LambdaOfMu {
                   return [a = n.param("alpha"), g = n.param("gamma"), how](double mu) {
                       return Lambda_gtr_interpolated(a, g, mu, how);
                   };
               },
               LambdaRoute::other});
}

VariantRegistry builtin_variants() {
    VariantRegistry r;
    register_core_variants(r);
    register_gtr_variants(r);
    return r;
}

NdfRegistry builtin_registry() {
    NdfRegistry r;
    register_core_ndfs(r);
    register_gtr_ndfs(r);
    return r;
}

}  // namespace smithlab
