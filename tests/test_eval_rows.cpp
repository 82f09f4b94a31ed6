// Every row `smithlab eval` (and the Python module, through the same evaluation::lambda_g1) prints agrees with itself:
// G1 = 1 / (1 + Lambda(|mu|)) to rounding, for every registered NDF at its example points, by every method and
// variant of `eval --list-methods` that applies to it, at mu from the largest double down to the smallest
// subnormal (the quadratures on fewer points, below). Where Lambda is +inf, G1 is 0 or so small that 1 / G1 - 1
// overflows too (an exact route's G1 by the grazing law); Lambda = 0 exactly where G1 = 1. Downward, Lambda(-mu) = -1 -
// Lambda(mu) and G1(-mu) = G1(mu).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "evaluation/route.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/registry.hpp"

using namespace smithlab;

namespace {

// Specs at every registered NDF's example points, and a table from experiments/ndfs/.
std::vector<std::string> all_examples(const NdfRegistry& registry) {
    std::vector<std::string> specs;
    for (const NdfInfo* info : registry.list()) specs.insert(specs.end(), info->examples.begin(), info->examples.end());
    specs.push_back("tabulated(file=" SMITHLAB_SOURCE_DIR "/experiments/ndfs/two_lobe.csv)");
    return specs;
}

// mu from the largest double to the smallest subnormal, 0 and inf with them.
const std::vector<double> mu_grid = {0.0,   5e-324, 1e-310, 1e-300, 1e-200, 1e-100, 1e-30, 1e-14,   1e-12,
                                     1e-10, 1e-8,   1e-6,   1e-4,   1e-3,   0.01,   0.1,   0.5,     1.0,
                                     2.0,   10.0,   1e3,    1e6,    1e12,   1e100,  1e300, DBL_MAX, INFINITY};
// The quadratures cost microseconds (1D) to milliseconds (2D) a point, each variant at several tolerances: their rows
// at the extremes, at the edges of the quadrature domain and a point a decade apart between them; the 2D routes at
// each family's first and last example point only.
const std::vector<double> mu_grid_quadrature = {0.0, 5e-324, 1e-310, 1e-300, 1e-13, 1e-12,   0.01,
                                                1.0, 1e3,    1e12,   1e13,   1e300, DBL_MAX, INFINITY};
enum class Cost { cheap, quadrature, nested };
Cost cost_of(const evaluation::Route& route, const AnyNdf& ndf) {
    if (route.variant) {
        const LambdaRoute r = route_on(*route.variant, ndf);
        return r == LambdaRoute::q2d_boost || r == LambdaRoute::q2d_gsl ? Cost::nested
            : is_quadrature(r)                                          ? Cost::quadrature
                                                                        : Cost::cheap;
    }
    switch (route.options.method) {
        case Method::quadrature2d:
            return Cost::nested;
        case Method::quadrature:
        case Method::fixed:
            return Cost::quadrature;
        case Method::automatic:
            return ndf.has_closed_Lambda() ? Cost::cheap : Cost::quadrature;
        default:
            return Cost::cheap;
    }
}

// The row's agreement, or what is wrong with it.
std::string disagreement(double lambda, double g1) {
    if (std::isnan(lambda) || std::isnan(g1)) return "NaN";
    if (!(g1 >= 0.0 && g1 <= 1.0)) return "g1 outside [0, 1]";
    if (!(lambda >= 0.0)) return "lambda < 0";
    if (lambda == 0.0 && g1 != 1.0) return "lambda = 0 with g1 < 1";
    if (lambda == INFINITY) return std::isfinite(1.0 / g1 - 1.0) ? "lambda = inf with 1 / g1 - 1 finite" : "";
    const double expected = 1.0 / (1.0 + lambda);
    return std::abs(g1 - expected) <= 2.0 * DBL_EPSILON * expected ? "" : "g1 != 1 / (1 + lambda)";
}

// The sweep over the routes of `costs`: every NDF's example points (the nested 2D routes at fewer, below), each mu of
// the route's grid and its negative: the routes applied, the rows and the rows at +inf.
struct Sweep {
    std::size_t applied = 0, rows = 0, at_infinity = 0;
};
Sweep sweep(const std::vector<Cost>& costs) {
    const NdfRegistry registry = builtin_registry();
    const VariantRegistry variants = builtin_variants();
    const std::vector<std::pair<std::string, std::string>> methods = evaluation::method_list(variants);
    const std::vector<std::string> specs = all_examples(registry);
    Sweep out;
    for (std::size_t i = 0; i < specs.size(); ++i) {
        const std::string& spec = specs[i];
        const AnyNdf ndf = registry.make(spec);
        const bool family_end = i == 0 || i + 1 == specs.size() ||
            registry.make(specs[i - 1]).family() != ndf.family() ||
            registry.make(specs[i + 1]).family() != ndf.family();
        for (const auto& [method, description] : methods) {
            const evaluation::Route route = evaluation::route({.method = method}, variants);
            if (route.variant && !route.variant->applies(ndf)) continue;
            const Cost cost = cost_of(route, ndf);
            if (std::find(costs.begin(), costs.end(), cost) == costs.end()) continue;
            // The nested routes at each family's ends; not on the table, whose C1 interpolant (a kink of D'' at every
            // row) takes the nested tanh-sinh minutes a point inside the quadrature's domain.
            if (cost == Cost::nested && (!family_end || ndf.family() == "tabulated")) continue;
            std::optional<evaluation::Prepared> p;
            try {
                p.emplace(evaluation::prepare(ndf, route));
            } catch (const input_error&) {
                continue;  // a core method the NDF lacks (closed, spline): refused by name, no row
            }
            ++out.applied;
            for (double mu : cost == Cost::cheap ? mu_grid : mu_grid_quadrature) {
                evaluation::LambdaG1 up{}, down{};
                try {
                    up = evaluation::lambda_g1(*p, mu, Downward::smith);
                    down = evaluation::lambda_g1(*p, -mu, Downward::smith);
                } catch (const input_error&) {
                    continue;  // mu in the band below the quadrature the NDF refuses (docs/accuracy-and-limits.md)
                }
                ++out.rows;
                out.at_infinity += up.lambda == INFINITY;
                INFO(spec << " --method " << method << " --mu " << mu << ": lambda " << up.lambda << ", g1 " << up.g1);
                CHECK(disagreement(up.lambda, up.g1) == "");
                if (mu > 0.0) {
                    INFO("at -mu: lambda " << down.lambda << ", g1 " << down.g1);
                    CHECK(down.g1 == up.g1);
                    CHECK(down.lambda == -1.0 - up.lambda);
                }
            }
        }
    }
    return out;
}

}  // namespace

// The counts make an empty sweep fail: every NDF had routes, most rows were computed, and the extremes were reached.
TEST_CASE("every eval row agrees with itself: the closed forms, splines, tables and approximations", "[eval]") {
    const Sweep s = sweep({Cost::cheap});
    CHECK(s.applied > builtin_registry().list().size() * 4);
    CHECK(s.rows > s.applied * mu_grid.size() / 2);
    CHECK(s.at_infinity > s.applied / 2);
}

TEST_CASE("every eval row agrees with itself: the 1D and nested 2D quadratures", "[eval][sweep]") {
    const Sweep s = sweep({Cost::quadrature, Cost::nested});
    CHECK(s.applied > builtin_registry().list().size() * 3);
    CHECK(s.rows > s.applied * mu_grid_quadrature.size() / 2);
    CHECK(s.at_infinity > s.applied / 2);
}
