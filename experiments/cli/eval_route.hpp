// What `smithlab eval` computes at a point: the route --method names, an NDF prepared for it, Lambda and G1.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "cli/commands.hpp"

namespace smithlab::cli {

// The route --method names: one of the core methods (method_names, with --backend and --tolerance), or a
// registered variant.
struct Route {
    LambdaOptions options;
    const LambdaVariant* variant = nullptr;
    // Lambda of ndf at a finite mu > 0, the variant prepared once per NDF (a table variant builds its table there);
    // a core method below its quadrature domain by the grazing law, computed once in `law`.
    LambdaOfMu prepare(const AnyNdf& ndf, const std::shared_ptr<GrazingLawOnce>& law) const;
};
Route route(const EvalArgs& args, const VariantRegistry& variants);

// What the route computes for `ndf` at mu, as eval's method line says it: the method's name, and for the quadratures
// their backend and tolerance ("auto (fixed rule, relative tolerance 1e-12; boost where its error estimate misses
// it)", "auto (closed form)"), or the grazing law below their domain ("quadrature (grazing law c/mu - 1/2 + P2(0)
// mu/2, grazing.hpp)").
std::string describe(const Route& route, const EvalArgs& args, const AnyNdf& ndf, double mu = NAN);

// An NDF of the input and its Lambda by the route, made once per spec; its grazing law (computed on first use) for
// the route's quadratures below their domain and for G1 wherever Lambda overflows (mu > 0 tiny).
struct Prepared {
    AnyNdf ndf;
    LambdaOfMu Lambda_up;
    std::shared_ptr<GrazingLawOnce> law;
    QuadratureOptions quadrature;
    // Whether Lambda = +inf at mu > 0 is the exact value overflowing (the closed forms and the quadratures), so that
    // G1 comes from the grazing law; an approximation's +inf (an interpolated G1 clamped to 0) keeps G1 = 0.
    bool exact = true;
};
Prepared prepare(const std::string& spec, const NdfRegistry& registry, const Route& route);
// The same for an NDF already made (the Python module's NDF objects).
Prepared prepare(AnyNdf ndf, const Route& route);

struct LambdaG1 {
    double lambda, g1;
};
// One Lambda evaluation serves both: G1 takes |mu| (Walter 2007 eq. 44), Lambda(mu < 0) follows the convention
// (the special values of mu: smith.hpp's Lambda_of_abs and Lambda_of_sign). G1 = 1 / (1 + Lambda(|mu|)) in every
// row, but where an exact route's Lambda overflows at mu != 0 (its forms overflow before c/mu does): there both come
// from the grazing law (grazing.hpp), Lambda = c/mu - 1/2 + .. and G1 = mu / (c + ..), Lambda +inf only where c/mu
// overflows and G1 then below 1 / DBL_MAX. An input_error names the NDF.
LambdaG1 lambda_g1(const Prepared& p, double mu, Downward downward);

}  // namespace smithlab::cli
