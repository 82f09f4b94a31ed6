// The route a method name picks for Lambda and G1, an NDF prepared for it, and its values at a point: what
// `smithlab eval --method` computes and what the Python module's Ndf.Lambda, G1 and G2 compute, one code for both.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/grazing.hpp"
#include "smithlab/smith.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::evaluation {

// The route as a front end names it: the command line from --method, --backend, --tolerance and --downward, the
// Python module from the keyword arguments of the same names. The defaults are both front ends' defaults.
struct RouteOptions {
    std::string method = "auto", backend = "boost", downward = "smith";
    double tolerance = 1e-12;  // relative, for the quadratures
};

// The bounds of the quadratures' relative tolerance that both front ends accept.
inline constexpr double min_tolerance = 1e-15, max_tolerance = 0.1;

// Every name a method may take, with its one-line description: the core methods (method_names), then the registered
// variants.
std::vector<std::pair<std::string, std::string>> method_list(const VariantRegistry& variants);

// The route a method name picks: one of the core methods (method_names, with the backend and tolerance), or a
// registered variant.
struct Route {
    LambdaOptions options;
    const LambdaVariant* variant = nullptr;
    // Lambda of ndf at a finite mu > 0, the variant prepared once per NDF (a table variant builds its table there);
    // a core method below its quadrature domain by the grazing law, computed once in `law`.
    LambdaOfMu prepare(const AnyNdf& ndf, const std::shared_ptr<GrazingLawOnce>& law) const;
};
// An unknown method, backend or downward convention is an input_error naming it.
Route route(const RouteOptions& options, const VariantRegistry& variants);

// What the route computes for `ndf` at mu, as eval's method line says it: the method's name, and for the quadratures
// their backend and tolerance ("auto (fixed rule, relative tolerance 1e-12; boost where its error estimate misses
// it)", "auto (closed form)"), or the grazing law below their domain ("quadrature (grazing law c/mu - 1/2 + P2(0)
// mu/2, grazing.hpp)").
std::string describe(const Route& route, const RouteOptions& options, const AnyNdf& ndf, double mu = NAN);

// An NDF and its Lambda by the route, made once per NDF; its grazing law (computed on first use) for the route's
// quadratures below their domain and for G1 wherever Lambda overflows (mu > 0 tiny).
struct Prepared {
    AnyNdf ndf;
    LambdaOfMu Lambda_up;
    std::shared_ptr<GrazingLawOnce> law;
    QuadratureOptions quadrature;
    // Whether Lambda = +inf at mu > 0 is the exact value overflowing (the closed forms and the quadratures), so that
    // G1 comes from the grazing law; an approximation's +inf (an interpolated G1 clamped to 0) keeps G1 = 0.
    bool exact = true;
};
// A route the NDF refuses (a core method it lacks, a variant that does not apply) is an input_error naming the NDF.
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

}  // namespace smithlab::evaluation
