// Quadrature Lambda (reduced 1D and nested 2D routes, Boost and GSL backends) against the 50-digit r-form reference.
// The accepted domain: alpha in [1e-4, 1], mu in [1e-4, 1e4], gamma in [0, 10], Blinn n in [0.5, 1000].
// Required: 1D <= 1e-10 everywhere; 2D <= 1e-8 for alpha >= 0.01, mu in [0.01, 100], gamma <= 4.
#include <gsl/gsl_errno.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <cfloat>
#include <random>
#include <smithlab/gtr.hpp>
#include <sstream>
#include <thread>

#include "reference.hpp"

using smithlab::Backend;

namespace {

struct Worst {
    double err = 0.0;
    std::string where;
    void add(double e, const std::string& w) {
        if (e > err) err = e, where = w;
    }
};

template <class N>
void check_1d(const N& ndf, const ref::SlopeDensity& f, double mu, const std::string& what, Worst& worst) {
    const ref::real want = ref::Lambda(f, mu);
    for (Backend b : {Backend::boost, Backend::gsl}) {
        const double got = smithlab::Lambda_1d(ndf, mu, {b, 1e-12});
        INFO(what << " mu=" << mu << " backend=" << smithlab::to_string(b) << " got=" << got);
        CHECK(ref::close(got, want, 1e-10));
        if (want >= DBL_MIN)
            worst.add(ref::rel_err(got, want),
                      what + " mu=" + std::to_string(mu) + " " + std::string(smithlab::to_string(b)));
    }
}

}  // namespace

TEST_CASE("1D quadrature Lambda of GTR over the domain, stiff corners included", "[quadrature][slow]") {
    Worst worst;
    const std::vector<double> gammas = {0.0, 0.5, 1.0 - 1e-9, 1.0, 1.0 + 1e-7, 1.5, 2.5, 4.0, 7.0, 10.0};
    const std::vector<double> alphas = {1e-4, 0.01, 0.3, 0.999999, 1.0};
    const std::vector<double> mus = {1e-4, 1e-2, 1.0, 1e2, 1e4};
    for (double g : gammas)
        for (double a : alphas)
            for (double mu : mus)
                check_1d(smithlab::gtr(a, g), ref::gtr(a, g), mu,
                         "gtr(alpha=" + std::to_string(a) + ", gamma=" + std::to_string(g) + ")", worst);
    WARN("worst 1D GTR relative error " << worst.err << " at " << worst.where);
}

TEST_CASE("1D quadrature Lambda at random points of the GTR domain", "[quadrature]") {
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Worst worst;
    for (int i = 0; i < 40; ++i) {
        const double a = std::pow(10.0, -4.0 * u(rng)), g = 10.0 * u(rng), mu = std::pow(10.0, -4.0 + 8.0 * u(rng));
        check_1d(smithlab::gtr(a, g), ref::gtr(a, g), mu,
                 "gtr(alpha=" + std::to_string(a) + ", gamma=" + std::to_string(g) + ")", worst);
    }
    // The worst point of the report's grid for GSL QAG at 1e-12 (it stops at 8.7e-12 there).
    check_1d(smithlab::gtr(0.000316227766016838, 3.5), ref::gtr(0.000316227766016838, 3.5), 1e-3, "gtr(3.16e-4, 3.5)",
             worst);
    WARN("worst 1D random-GTR relative error " << worst.err << " at " << worst.where);
}

TEST_CASE("1D quadrature Lambda of Blinn-Phong, Beckmann and GGX", "[quadrature]") {
    Worst worst;
    for (double n : {0.5, 20.0, 1000.0})
        for (double mu : {1e-4, 1e-2, 0.3, 1.0, 1e2, 1e4})
            check_1d(smithlab::blinn(n), ref::blinn(n), mu, "blinn(n=" + std::to_string(n) + ")", worst);
    for (double a : {1e-4, 0.05, 1.0})
        for (double mu : {1e-4, 1e-2, 1.0, 1e2}) {
            // Beckmann at mu/alpha >= 27 underflows: Lambda ~ exp(-(mu/alpha)^2). Below, its reference is
            // the closed form at 50 digits.
            if (mu / a > 25) continue;
            const ref::real want = ref::Lambda_beckmann(a, mu);
            for (Backend b : {Backend::boost, Backend::gsl}) {
                INFO("beckmann alpha=" << a << " mu=" << mu << " " << smithlab::to_string(b));
                CHECK(ref::close(smithlab::Lambda_1d(smithlab::beckmann(a), mu, {b, 1e-12}), want, 1e-10));
            }
        }
    for (double a : {1e-4, 0.3})
        for (double mu : {1e-4, 1.0, 1e4})
            check_1d(smithlab::ggx(a), ref::ggx(a), mu, "ggx(alpha=" + std::to_string(a) + ")", worst);
    WARN("worst 1D Blinn/GGX relative error " << worst.err << " at " << worst.where);
}

TEST_CASE("Nested 2D route P22 -> P2 -> Lambda", "[quadrature][2d][sweep]") {
    double worst = 0.0;
    for (double g : {0.0, 1.0, 2.5, 4.0})
        for (double a : {0.01, 0.3, 1.0})
            for (double mu : {0.01, 1.0, 100.0}) {
                const ref::real want = ref::Lambda(ref::gtr(a, g), mu);
                for (Backend b : {Backend::boost, Backend::gsl}) {
                    const double got = smithlab::Lambda_2d(smithlab::gtr(a, g), mu, {b, 1e-10});
                    INFO("gamma=" << g << " alpha=" << a << " mu=" << mu << " " << smithlab::to_string(b));
                    CHECK(ref::close(got, want, 1e-8));
                    worst = std::max(worst, ref::rel_err(got, want));
                }
            }
    WARN("worst 2D relative error " << worst);
}

TEST_CASE("P2 of GGX against its closed form (Walter 2007 / Hammon appendix)", "[quadrature]") {
    for (double a : {0.01, 0.3, 1.0})
        for (double q : {0.0, 0.01, 1.0, 100.0}) {
            const double want = a * a / (2.0 * std::pow(q * q + a * a, 1.5));
            for (Backend b : {Backend::boost, Backend::gsl}) {
                INFO("alpha=" << a << " q=" << q);
                CHECK(std::abs(smithlab::P2(smithlab::ggx(a), q, {b, 1e-12}) - want) <= 1e-11 * want);
            }
        }
}

TEST_CASE("quadrature holds to the ends of its range, mu in [1e-12, 1e12], and refuses beyond", "[quadrature]") {
    for (double a : {1e-4, 0.3, 1.0})
        for (int g : {0, 1, 3, 4})
            for (double mu : {1e-12, 1e-8, 1e8, 1e12})
                for (Backend b : {Backend::boost, Backend::gsl}) {
                    const auto ndf = smithlab::gtr(a, g);
                    const double want = ndf.Lambda(mu);  // closed form, itself checked at 50 digits
                    INFO("alpha=" << a << " gamma=" << g << " mu=" << mu << " " << smithlab::to_string(b));
                    CHECK(std::abs(smithlab::Lambda_1d(ndf, mu, {b, 1e-12}) - want) <= 1e-10 * want);
                }
    for (double mu : {1e-12, 1e12}) {
        INFO("mu=" << mu);
        CHECK(std::abs(smithlab::Lambda_1d(smithlab::beckmann(0.2), mu) - smithlab::beckmann(0.2).Lambda(mu)) <=
              1e-10 * smithlab::beckmann(0.2).Lambda(mu));
        CHECK(std::isfinite(smithlab::Lambda_1d(smithlab::blinn(1000), mu)));
    }
    CHECK_THROWS_AS(smithlab::Lambda_1d(smithlab::ggx(0.3), 1e-13), smithlab::input_error);
    CHECK_THROWS_AS(smithlab::Lambda_1d(smithlab::ggx(0.3), 1e13), smithlab::input_error);
}

// The decade points above missed it: between them, Boost's tanh-sinh took the grazing peak (s = pi/2 - t ~ mu/alpha)
// for converged in narrow windows of mu, when it fell between the nodes of two successive levels alike -- Beckmann(1)
// 59 % low at mu in [1.76e-12, 2.22e-12], 47 % at [4.5e-11, 5.0e-11], 35 % at [7.9e-10, 8.0e-10], 0.56 % at
// [1.37e-8, 1.39e-8], 19 windows up to mu = 5e-6; GGX(1) 5.6e-5, GTR(0.5, 4) 1.7e-3. The t-form integrals now
// split at s = mu/r0 and s = mu (integrate_quarter_turn's breaks). Every 1/100 decade and every window, both backends.
TEST_CASE("1D quadrature at grazing: every 1/100 decade of mu in [1e-12, 1] r0 against the closed forms",
          "[quadrature]") {
    std::vector<double> mus;
    for (int k = 0; k <= 1200; ++k) mus.push_back(std::pow(10.0, -12.0 + k / 100.0));
    for (double m : {1.9e-12,  2.2e-12,    2.9e-12,  2.98e-12,  4.4235e-12, 6.695e-12, 6.8e-12,  1.0087e-11, 4.7e-11,
                     5.0e-11,  7.03e-11,   1.46e-10, 7.95e-10,  8.0e-10,    1.155e-9,  1.38e-8,  1.2435e-7,  8.765e-7,
                     4.969e-6, 8.2177e-12, 1.67e-10, 1.215e-12, 1.14e-12,   2.59e-12,  5.42e-11, 7.975e-10})
        mus.push_back(m);
    Worst worst;
    auto check = [&](const auto& ndf, double r0, const std::string& name) {
        for (double m : mus)
            for (Backend b : {Backend::boost, Backend::gsl}) {
                const double mu = m * r0, want = ndf.Lambda(mu);
                if (mu < 1e-12) continue;  // the quadrature methods' range
                std::ostringstream at;
                at << name << " mu=" << mu << " " << smithlab::to_string(b);
                worst.add(std::abs(smithlab::Lambda_1d(ndf, mu, {b, 1e-12}) - want) / want, at.str());
            }
    };
    check(smithlab::beckmann(1.0), 1.0, "beckmann(1)");
    check(smithlab::beckmann(0.01), 0.01, "beckmann(0.01)");
    check(smithlab::ggx(1.0), 1.0, "ggx(1)");
    check(smithlab::gtr(0.5, 4.0), 1.0, "gtr(0.5,4)");
    check(smithlab::gtr(0.01, 3.0), 1.0, "gtr(0.01,3)");
    INFO("worst " << worst.err << " at " << worst.where);
    CHECK(worst.err <= 1e-10);
}

TEST_CASE("Nested 2D route holds outside its required domain too: the corners where a fixed-scale map fails",
          "[quadrature][2d][sweep]") {
    // A semi-infinite map with a fixed unit scale (GSL QAGIU as is) misses a peak of width 1e-4 and the 1e4-long
    // tail: it returned 0 for Beckmann(1e-4) at mu = 1e-4 and 7.7% low at mu = 1e4. The tan/sec maps have no scale.
    struct Case {
        const char* what;
        ref::SlopeDensity f;
        smithlab::AnyNdf ndf;
        double mu;
    };
    const auto reg = smithlab::builtin_registry();
    const std::vector<Case> cases = {
        {"gtr(1e-4, 0)", ref::gtr(1e-4, 0.0), reg.make("gtr(alpha=1e-4, gamma=0)"), 1e4},
        {"gtr(1e-4, 10)", ref::gtr(1e-4, 10.0), reg.make("gtr(alpha=1e-4, gamma=10)"), 1e4},
        {"gtr(1e-4, 10)", ref::gtr(1e-4, 10.0), reg.make("gtr(alpha=1e-4, gamma=10)"), 1e-4},
        {"gtr(1, 10)", ref::gtr(1.0, 10.0), reg.make("gtr(alpha=1, gamma=10)"), 1e-4},
        {"beckmann(1e-4)", ref::beckmann(1e-4), reg.make("beckmann(alpha=1e-4)"), 1e-4},
        {"blinn(0.5)", ref::blinn(0.5), reg.make("blinn(n=0.5)"), 1e4},
        {"blinn(1000)", ref::blinn(1000.0), reg.make("blinn(n=1000)"), 1e-4},
    };
    for (const Case& c : cases) {
        const ref::real want = ref::Lambda(c.f, c.mu);
        for (Backend b : {Backend::boost, Backend::gsl}) {
            const double got = smithlab::Lambda_2d(c.ndf, c.mu, {b, 1e-10});
            INFO(c.what << " mu=" << c.mu << " " << smithlab::to_string(b) << " got=" << got);
            CHECK(ref::close(got, want, 1e-8));
        }
    }
}

// GSL's error handler (quadrature.hpp, "Threads"): switched off once, never set and restored around a call.
// sqrt(x) on [0, 1] at the tightest tolerance makes QAG report GSL_EROUND on every call (after 35 intervals).
TEST_CASE("GSL's error handler: off from the first GSL integration on, and no call touches it again", "[quadrature]") {
    auto root = [](double x) { return std::sqrt(x); };
    CHECK(std::abs(smithlab::integrate(root, 0.0, 1.0, {Backend::gsl, 1e-14}) - 2.0 / 3.0) <= 1e-14);
    gsl_error_handler_t* off = gsl_set_error_handler(nullptr);  // reads it (nullptr: GSL's default, which aborts)
    CHECK(off != nullptr);
    // A handler installed now receives the report of the next call: smithlab did not switch it off for the call.
    static int reports = 0;
    gsl_set_error_handler([](const char*, const char*, int, int) { ++reports; });
    (void)smithlab::integrate(root, 0.0, 1.0, {Backend::gsl, 1e-14});
    gsl_set_error_handler(off);
    CHECK(reports == 1);
}

TEST_CASE("GSL integrations in four threads at once: the results of one thread, and no abort", "[quadrature]") {
    // With the handler set off and restored around each call, one thread's restore re-armed GSL's abort under
    // another's call: this aborted in 9 of 10 runs of 4 x 250 calls.
    auto root = [](double x) { return std::sqrt(x); };
    const double one = smithlab::integrate(root, 0.0, 1.0, {Backend::gsl, 1e-14});
    std::atomic<int> differ{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&] {
            for (int i = 0; i < 1000; ++i)
                if (smithlab::integrate(root, 0.0, 1.0, {Backend::gsl, 1e-14}) != one) ++differ;
        });
    for (std::thread& t : threads) t.join();
    CHECK(differ == 0);
}

// ---- the fixed rule (lambda_fixed.hpp, method `fixed`) -------------------------------------------------------------
// Gauss-Kronrod 15-31 panels on precomputed nodes. What is checked: (1) its relative error in Lambda against
// independent references -- the closed forms (GGX, Beckmann, GTR at integer gamma, each checked at 50 digits
// elsewhere) and the 50-digit r-form reference (GTR at real gamma, Blinn-Phong); (2) that its error estimate is a
// bound: |error| <= E + the rounding floor of the integrand, 4 eps (1 + (mu/alpha)^2 for Beckmann, whose
// exp(-r^2/alpha^2) carries a relative error ~(r/alpha)^2 eps at the integrand's bulk, r ~ mu); (3) that
// Lambda_fixed (the rule, or the adaptive route where E misses the tolerance) is within 1e-12 everywhere, stiff
// corners included.
namespace {

struct FixedWorst {
    double err = 0.0, bound_ratio = 0.0;
    std::string where;
    int not_converged = 0, evaluations_max = 0;
};

// One point: the rule alone (error, estimate, convergence) and the public route.
template <class N>
void check_fixed(const N& ndf, double mu, double want, double floor, const std::string& what, FixedWorst& w,
                 bool must_converge = true) {
    const smithlab::FixedLambda r = smithlab::Lambda_fixed_rule(ndf, mu, 1e-12);
    const double got = smithlab::Lambda_fixed(ndf, mu, {Backend::gsl, 1e-12});
    INFO(what << " mu=" << mu << " want=" << want << " rule=" << r.Lambda << " E=" << r.error
              << " converged=" << r.converged << " evaluations=" << r.evaluations << " Lambda_fixed=" << got);
    if (!(want >= DBL_MIN)) return;  // underflowed: nothing relative to check
    const double err = std::abs(got - want) / want;
    CHECK(err <= 1e-12);
    if (must_converge) CHECK(r.converged);
    if (!r.converged) {
        ++w.not_converged;
        return;
    }
    const double rule_err = std::abs(r.Lambda - want) / want, bound = r.error / want + floor;
    CHECK(rule_err <= bound);
    w.evaluations_max = std::max(w.evaluations_max, r.evaluations);
    w.bound_ratio = std::max(w.bound_ratio, rule_err / bound);
    if (rule_err > w.err) w.err = rule_err, w.where = what + " mu=" + std::to_string(mu);
}

constexpr double eps4 = 4.0 * DBL_EPSILON;

}  // namespace

TEST_CASE("fixed rule: Lambda of GGX, Beckmann and GTR at integer gamma against their closed forms",
          "[quadrature][fixed]") {
    FixedWorst w;
    const std::vector<double> mus = {1e-12, 1e-8, 1e-6, 1e-4, 1e-3, 0.01,  0.05, 0.1, 0.3,
                                     0.7,   1.0,  2.0,  5.0,  10.0, 100.0, 1e4,  1e8, 1e12};
    for (double a : {1e-4, 1e-3, 0.01, 0.1, 0.3, 0.5, 0.999999, 1.0})
        for (double mu : mus) {
            const auto g = smithlab::ggx(a);
            check_fixed(g, mu, g.Lambda(mu), eps4, "ggx(" + std::to_string(a) + ")", w);
            const auto b = smithlab::beckmann(a);
            // Beckmann's Lambda ~ exp(-(mu/alpha)^2) underflows past mu/alpha ~ 27.
            if (mu / a <= 25.0)
                check_fixed(b, mu, b.Lambda(mu), eps4 * (1.0 + (mu / a) * (mu / a)),
                            "beckmann(" + std::to_string(a) + ")", w);
        }
    for (int gamma : {0, 1, 3, 4, 7, 12})
        for (double a : {1e-4, 0.01, 0.3, 1.0})
            for (double mu : mus) {
                const auto n = smithlab::gtr(a, gamma);
                check_fixed(n, mu, smithlab::Lambda(n, mu, {.method = smithlab::Method::closed}), eps4,
                            "gtr(" + std::to_string(a) + ", " + std::to_string(gamma) + ")", w);
            }
    WARN("fixed rule against closed forms: worst relative error "
         << w.err << " at " << w.where << "; worst error / bound " << w.bound_ratio << "; most evaluations "
         << w.evaluations_max);
}

TEST_CASE("fixed rule: GTR at real gamma and Blinn-Phong against the 50-digit reference", "[quadrature][fixed]") {
    FixedWorst w;
    for (double gamma : {0.0, 0.5, 1.0 - 1e-9, 1.0 + 1e-9, 1.5, 2.5, 10.0})
        for (double a : {1e-4, 0.05, 1.0})
            for (double mu : {1e-8, 1e-4, 0.03, 1.0, 30.0, 1e4})
                check_fixed(smithlab::gtr(a, gamma), mu, static_cast<double>(ref::Lambda(ref::gtr(a, gamma), mu)), eps4,
                            "gtr(" + std::to_string(a) + ", " + std::to_string(gamma) + ")", w);
    for (double n : {1.0, 20.0, 1000.0})
        for (double mu : {1e-4, 0.03, 1.0, 30.0, 1e4})
            check_fixed(smithlab::blinn(n), mu, static_cast<double>(ref::Lambda(ref::blinn(n), mu)), eps4,
                        "blinn(" + std::to_string(n) + ")", w);
    WARN("fixed rule against the 50-digit reference: worst relative error "
         << w.err << " at " << w.where << "; worst error / bound " << w.bound_ratio << "; most evaluations "
         << w.evaluations_max);
}

TEST_CASE("fixed rule: the stiff corners, where the estimate sends it to bisection or to the adaptive route",
          "[quadrature][fixed]") {
    FixedWorst w;
    // Blinn-Phong n -> 0: a slope tail r^-(4 + n), whose s^n at the tail's end point no polynomial rule follows.
    for (double n : {0.01, 0.1, 0.5})
        for (double mu : {1e-4, 1.0, 1e4})
            check_fixed(smithlab::blinn(n), mu, static_cast<double>(ref::Lambda(ref::blinn(n), mu)), eps4,
                        "blinn(" + std::to_string(n) + ")", w, false);
    // Beckmann far from the pole (mu/alpha up to 25: a Gaussian in u of width alpha/mu at u = 0); GGX and Beckmann
    // with mu ~ alpha at alpha = 1e-4; D-only NDFs (slopes through cos theta_m).
    for (double ratio : {5.0, 12.0, 25.0}) {
        const auto b = smithlab::beckmann(1e-4);
        check_fixed(b, ratio * 1e-4, b.Lambda(ratio * 1e-4), eps4 * (1.0 + ratio * ratio), "beckmann(1e-4)", w, false);
    }
    for (double mu : {1e-5, 1e-4, 2e-4}) {
        const auto g = smithlab::ggx(1e-4);
        check_fixed(g, mu, g.Lambda(mu), eps4, "ggx(1e-4)", w);
    }
    for (double mu : {1e-3, 1.0, 1e3}) {
        const smithlab::DOnly<smithlab::Ggx> d{smithlab::ggx(0.2)};
        check_fixed(d, mu, smithlab::ggx(0.2).Lambda(mu), 1e-14, "D-only ggx(0.2)", w);
    }
    WARN("fixed rule at the stiff corners: worst relative error of the converged rule "
         << w.err << " at " << w.where << "; not converged (adaptive route) " << w.not_converged);
}

TEST_CASE("fixed rule: method 'fixed' through Lambda/G1, and the domain of the quadrature methods",
          "[quadrature][fixed]") {
    const auto n = smithlab::gtr(0.3, 1.5);
    const smithlab::LambdaOptions fixed{.method = smithlab::Method::fixed};
    const double q = smithlab::Lambda(n, 0.7, {.method = smithlab::Method::quadrature, .tolerance = 1e-13});
    CHECK(std::abs(smithlab::Lambda(n, 0.7, fixed) - q) <= 1e-12 * q);
    CHECK(smithlab::Lambda(n, -0.7, fixed) == -1.0 - smithlab::Lambda(n, 0.7, fixed));
    CHECK(smithlab::Lambda(n, 0.0, fixed) == INFINITY);
    CHECK(smithlab::G1(n, INFINITY, fixed) == 1.0);
    CHECK_THROWS_AS(smithlab::Lambda_fixed(n, 1e-13), smithlab::input_error);
    CHECK_THROWS_AS(smithlab::Lambda_fixed(n, 1e13), smithlab::input_error);
    CHECK_THROWS_AS(smithlab::Lambda_fixed(n, 1.0, {Backend::gsl, 0.0}), smithlab::input_error);
    // Type-erased NDFs take the same rule.
    const smithlab::AnyNdf any = smithlab::builtin_registry().make("gtr(alpha=0.3, gamma=1.5)");
    CHECK(std::abs(smithlab::Lambda_fixed(any, 0.7) - q) <= 1e-12 * q);
}
