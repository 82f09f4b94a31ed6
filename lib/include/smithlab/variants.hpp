/// @file
/// smithlab/variants.hpp -- named ways to compute Lambda, side by side: exact routes at several tolerances,
/// interpolants, and the approximations renderers use. `smithlab eval --method NAME`, `--list-methods` and the
/// error-against-run-time report all go through this one interface.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

/// Lambda of one NDF as a function of mu.
using LambdaOfMu = std::function<double(double mu)>;

/// The route a variant computes Lambda by, so that a check can take another (the report's references).
enum class LambdaRoute {
    closed,     ///< the NDF's closed form
    q1d_boost,  ///< the reduced 1D quadrature (Lambda_1d), Boost tanh-sinh, at any tolerance
    q2d_boost,  ///< the nested 2D quadrature (Lambda_2d), Boost
    q1d_gsl,    ///< Lambda_1d, GSL QAG
    q2d_gsl,    ///< Lambda_2d, GSL QAG
    table,      ///< tabulated from the exact route: the closed form where the NDF has one, else the fixed rule (Boost
                ///< 1D where its estimate misses)
    other,      ///< an approximation or an interpolant: none of the above
};

/// A named way to compute Lambda (an exact route, an interpolant or an approximation), prepared once per NDF.
struct LambdaVariant {
    /// The name `--method` and the report know it by, and a one-line description for `--list-methods`.
    /// @{
    std::string name;
    std::string description;
    /// @}
    std::function<bool(const AnyNdf&)> applies;  ///< the NDFs it is defined for
    /// The per-NDF work (reading its parameters, building a table) done once; what it returns evaluates Lambda at
    /// finite mu > 0, as often as the caller likes.
    std::function<LambdaOfMu(const AnyNdf&)> prepare;
    /// The route it computes Lambda by (route_on: a table's, the route it was built from).
    LambdaRoute route = LambdaRoute::other;
    /// Why it does not apply to an NDF applies() refuses, naming the parameter, its value and the domain it covers
    /// ("method 'family' covers gtr with gamma in [0, 20]; got gamma = 21"); unset: a message naming the NDF's family.
    std::function<std::string(const AnyNdf&)> refusal = {};
};

/// The route variant takes on ndf: a table's is the route it was built from (closed or q1d_boost), the others' their
/// own.
LambdaRoute route_on(const LambdaVariant& variant, const AnyNdf& ndf);
/// Lambda_1d or Lambda_2d, by either backend.
bool is_quadrature(LambdaRoute route);

/// The variants by name, in registration order.
class VariantRegistry {
public:
    void add(LambdaVariant v);  ///< input_error on a duplicate name
    /// The variant named `name`, or nullptr.
    const LambdaVariant* find(std::string_view name) const;
    const LambdaVariant& at(std::string_view name) const;  ///< input_error naming the unknown variant
    /// Every variant, in registration order.
    const std::vector<LambdaVariant>& list() const { return variants_; }

private:
    std::vector<LambdaVariant> variants_;
};

/// A variant prepared for ndf, taking any mu: 0 and inf exact, mu < 0 by the convention, input_error on NaN.
/// input_error if the variant does not apply to ndf (its refusal's message where it has one).
LambdaOfMu prepare(const LambdaVariant& variant, const AnyNdf& ndf, Downward downward = Downward::smith);
/// One evaluation (prepares each time: for many mu, prepare once).
double Lambda(const LambdaVariant& variant, const AnyNdf& ndf, double mu, Downward downward = Downward::smith);

/// q1d-{boost,gsl}-{1e-4..1e-12}, q2d-{boost,gsl}-{1e-4,1e-6,1e-8}, closed-form, table (lambda_table.hpp), schlick-ggx,
/// beckmann-rational.
void register_core_variants(VariantRegistry& registry);

/// The approximations, as free functions (each cites its source).
/// Hammon 2017, "Smith: Approximate GGX G1": G1 ~ 2 NdotV / (NdotV (2 - alpha) + alpha), identical to Unreal's
/// Schlick-style G1 with k = alpha/2. Its Lambda = alpha (1 - NdotV)/(2 NdotV) = alpha / (2 mu (mu + sqrt(mu^2 + 1))).
double Lambda_schlick_ggx(double alpha, double mu);
/// Walter 2007 eq. 27, rational approximation of Beckmann's G1 in a = mu/alpha: (3.535a + 2.181a^2) /
/// (1 + 2.276a + 2.577a^2) for a < 1.6, else 1; as Lambda, (1 - 1.259a + 0.396a^2)/(3.535a + 2.181a^2) or 0.
double Lambda_beckmann_rational(double alpha, double mu);

/// G2 for two directions on the same side (reflection), against the exact height-correlated 1/(1 + Li + Lo).
struct G2Variant {
    /// Its name and a one-line description, and the NDFs it is defined for.
    /// @{
    std::string name;
    std::string description;
    std::function<bool(const AnyNdf&)> applies;
    /// @}
    std::function<double(const AnyNdf&, double mu_i, double mu_o)> G2;  ///< for finite mu > 0
};

/// g2-uncorrelated (exact G1 G1), g2-schlick-uncorrelated (Hammon/Unreal G1 G1), g2-hammon-lerp.
std::vector<G2Variant> builtin_G2_variants();

/// Hammon 2017, "Smith: Approximate GGX G2": G2 ~ 2 NL NV / lerp(2 NL NV, NL + NV, alpha), with N.X = mu/sqrt(1+mu^2).
double G2_hammon_lerp(double alpha, double mu_i, double mu_o);

}  // namespace smithlab
