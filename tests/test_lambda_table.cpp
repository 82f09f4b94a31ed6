// The tabulated Lambda (lambda_table.hpp), the fast evaluator for any real gamma: against routes it is not built
// from (the nested 2D quadrature, the closed forms, the 50-digit reference), and its error estimate against the
// error measured.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <smithlab/smithlab.hpp>

#include "grid.hpp"
#include "reference.hpp"

using namespace smithlab;

namespace {

struct Worst {
    double rel = 0.0, dG1 = 0.0;
    void add(double got, double want) {
        rel = std::max(rel, std::abs(got - want) / want);
        dG1 = std::max(dG1, std::abs(1.0 / (1.0 + got) - 1.0 / (1.0 + want)));
    }
};

}  // namespace

TEST_CASE("table: the fast-evaluator target over alpha in [1e-4, 1], mu in [1e-4, 1e4], any real gamma in [0, 20]",
          "[table]") {
    // Random (alpha, gamma), the stiff corners among them; 12 random mu per table against the nested 2D route.
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0), log_mu(std::log(1e-4), std::log(1e4));
    std::vector<std::pair<double, double>> cases = {{1e-4, 0.0},  {1e-4, 0.5}, {1e-4, 1.0 - 1e-9}, {1e-4, 1.0 + 1e-9},
                                                    {1e-4, 1.5},  {1e-4, 19.7}, {1.0, 0.3},        {0.999999, 7.5},
                                                    {0.3, 1.25}, {1e-3, 20.0}};
    for (int k = 0; k < 14; ++k) cases.emplace_back(std::exp(log_alpha(rng)), gamma_u(rng));
    Worst all;
    for (const auto& [alpha, gamma] : cases) {
        const Gtr ndf = gtr(alpha, gamma);
        const LambdaTable table = tabulate_Lambda(ndf);
        Worst w;
        for (int i = 0; i < 12; ++i) {
            const double mu = std::exp(log_mu(rng));
            w.add(table.Lambda(mu), Lambda_2d(ndf, mu, {Backend::gsl, 1e-11}));
        }
        for (double mu : {1e-4, 1e4}) w.add(table.Lambda(mu), Lambda_2d(ndf, mu, {Backend::gsl, 1e-11}));
        INFO("gtr(" << alpha << ", " << gamma << "): worst relative dLambda " << w.rel << ", estimate "
                    << table.error_estimate() << ", |dG1| " << w.dG1 << ", " << table.knots() << " knots");
        CHECK(w.rel <= table.error_estimate());  // the estimate holds
        CHECK(table.error_estimate() <= 1e-6);
        all.rel = std::max(all.rel, w.rel);
        all.dG1 = std::max(all.dG1, w.dG1);
    }
    WARN("table: worst relative dLambda " << all.rel << ", worst |dG1| " << all.dG1);
    CHECK(all.rel <= 1e-5);  // the target
    CHECK(all.dG1 <= 1e-6);
    CHECK(all.rel > 1e-10);  // a table, not the exact route in disguise
}

TEST_CASE("table: against the 50-digit reference at the stiff corners and the generated closed forms", "[table]") {
    for (const auto& [alpha, gamma, mu] : {std::tuple{1e-4, 0.5, 1e-4}, std::tuple{1e-4, 1.0 + 1e-9, 3e-3},
                                           std::tuple{0.02, 13.3, 0.05}, std::tuple{0.9, 0.1, 1e4}}) {
        const double got = tabulate_Lambda(gtr(alpha, gamma)).Lambda(mu);
        INFO("gtr(" << alpha << ", " << gamma << ") mu=" << mu);
        CHECK(ref::close(got, ref::Lambda(ref::gtr(alpha, gamma), mu), 1e-6));
    }
    for (int gamma : {0, 2, 5, 10, 20}) {
        const Gtr ndf = gtr(0.01, gamma);
        const LambdaTable table = tabulate_Lambda(ndf, {.exact = {.method = Method::quadrature}});
        for (double mu : grid::logspace(1e-4, 1e4, 33)) {
            INFO("gamma=" << gamma << " mu=" << mu);
            CHECK(std::abs(table.Lambda(mu) / ndf.Lambda(mu) - 1.0) <= table.error_estimate());
        }
    }
}

TEST_CASE("table: outside its range, and where Lambda underflows, the exact route answers", "[table]") {
    const Ggx ggx = smithlab::ggx(0.2);
    const LambdaTable t = tabulate_Lambda(ggx);
    for (double mu : {1e-9, 1e-6, 1e6, 1e12}) CHECK(t.Lambda(mu) == ggx.Lambda(mu));
    CHECK(t.Lambda(0.0) == INFINITY);
    CHECK(t.Lambda(INFINITY) == 0.0);
    CHECK(t.Lambda(-2.0) == -1.0 - ggx.Lambda(2.0));
    CHECK(t.G1(-2.0) == Approx(1.0 / (1.0 + ggx.Lambda(2.0))).epsilon(1e-6));

    // Beckmann: Lambda ~ exp(-mu^2/alpha^2) underflows near mu = 27 alpha; the table stops a pad short of it.
    const Beckmann b = beckmann(0.3);
    const LambdaTable tb = tabulate_Lambda(b);
    CHECK(tb.mu_max() < 27 * 0.3);
    CHECK(tb.mu_max() > 0.3);
    for (double mu : grid::logspace(1e-4, 1e4, 41)) {
        INFO("beckmann(0.3) mu=" << mu);
        if (mu > tb.mu_max()) CHECK(tb.Lambda(mu) == b.Lambda(mu));
        else CHECK(std::abs(tb.Lambda(mu) / b.Lambda(mu) - 1.0) <= tb.error_estimate());
    }
}

TEST_CASE("table: bad options and a bad exact route are errors that name the item", "[table]") {
    const Ggx g = ggx(0.3);
    auto message = [&](const LambdaTableOptions& o) {
        try {
            tabulate_Lambda(g, o);
        } catch (const input_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(message({.mu_min = 0.0}), Catch::Contains("mu_min"));
    CHECK_THAT(message({.mu_min = NAN}), Catch::Contains("mu_min"));
    CHECK_THAT(message({.mu_max = 1e-6}), Catch::Contains("mu_max"));
    CHECK_THAT(message({.tolerance = 0.0}), Catch::Contains("tolerance"));
    CHECK_THAT(message({.tolerance = 1e-16}), Catch::Contains("cannot tabulate"));
    CHECK_THROWS_WITH(LambdaTable([](double mu) { return mu > 10.0 ? NAN : 1.0 / mu; }, {}),
                      Catch::Contains("cannot tabulate") && Catch::Contains("mu = 1"));
}
