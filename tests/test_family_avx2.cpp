// The family evaluator's stream on its AVX2 route (gtr/family_stream.hpp, GtrFamilyRoute::avx2), run by name so that
// a CPU with AVX-512 runs it too: the same G1 as the one call (GtrFamily::G1_up) to rounding over the whole domain and
// its stiff corners, the stated bound (|dG1| <= 1e-6) against independent routes (closed forms, tanh-sinh, the
// 50-digit reference), the special values, any length, in place; and the same values as the AVX-512 route where the
// CPU runs both.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <smithlab/gtr.hpp>
#include <smithlab/gtr/family.hpp>
#include <smithlab/gtr/family_stream.hpp>
#include <tuple>
#include <vector>

#include "reference.hpp"

using namespace smithlab;

namespace {

constexpr GtrFamilyRoute avx2 = GtrFamilyRoute::avx2;

// An independent Lambda: the closed form at integer gamma, else the adaptive tanh-sinh route (the tree's knots are
// trapezoid strips).
double independent(double alpha, double gamma, double mu) {
    const Gtr n = gtr(alpha, gamma);
    return gtr_has_closed_form(gamma) ? n.Lambda(mu) : Lambda_1d(n, mu, {Backend::boost, 1e-12});
}

struct Points {
    std::vector<double> alpha, gamma, mu;
    void add(double a, double g, double m) { alpha.push_back(a), gamma.push_back(g), mu.push_back(m); }
    std::vector<double> G1(GtrFamilyRoute route) const {
        std::vector<double> out(mu.size());
        GtrFamilyStream::get().G1_up(route, alpha.data(), gamma.data(), mu.data(), out.data(), out.size());
        return out;
    }
};

// The stiff corners of test_family.cpp: the ends of alpha, gamma at and near the closed forms' integers, mu over 16
// decades.
Points corners() {
    Points p;
    for (double a : {1e-4, 1.5e-4, 0.999999, 1.0})
        for (double g : {0.0, 1e-9, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 1.5, 2.0, 19.99, 20.0})
            for (double m : {1e-8, 3e-7, 1e-4, 0.01, 1.0, 3.0, 1e4, 1e8}) p.add(a, g, m);
    return p;
}

}  // namespace

TEST_CASE("family stream AVX2: this machine runs the route", "[family]") {
    const GtrFamilyStream& stream = GtrFamilyStream::get();
    WARN("family stream: chosen route " << name(stream.route()) << "; AVX2 route "
                                        << (stream.runs(avx2) ? "runs here" : "does not run here"));
#if defined(__x86_64__) && defined(__GLIBC__)
    // an x86-64 glibc build has the route (libmvec); it runs wherever the CPU has AVX2 and FMA
    __builtin_cpu_init();
    const bool cpu = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    CHECK(stream.runs(avx2) == cpu);
    if (cpu && !stream.runs(GtrFamilyRoute::avx512)) CHECK(stream.route() == avx2);
#else
    CHECK(!stream.runs(avx2));  // elsewhere the route is not built: G1_up(avx2, ...) is the one call in a loop
#endif
}

TEST_CASE("family stream AVX2: the same G1 as one point at a time, over the whole domain and its corners", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    Points p = corners();
    std::mt19937_64 rng(45);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0), gamma_low(0.0, 3.0),
        log_mu(-25.0, 25.0);
    for (int i = 0; i < 20000; ++i)
        p.add(std::exp(log_alpha(rng)), i % 3 == 0 ? gamma_low(rng) : gamma_u(rng), std::exp(log_mu(rng)));
    for (double m : {-0.3, -1e-8, 5e-324, 1e-300, 1e300}) p.add(0.2, 1.5, m);  // G1 takes |mu|; the asymptotes
    const std::vector<double> got = p.G1(avx2);
    // the same leaves by another route: |dG1| <= 1e-12 G1 (1 - G1) (relative dLambda <= 1e-12) plus two ulps of 1
    double worst = 0.0;
    std::size_t at = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        const double want = t.G1_up(p.alpha[i], p.gamma[i], std::abs(p.mu[i]));
        const double allowed = 1e-12 * want * (1.0 - want) + 4.5e-16, ratio = std::abs(got[i] - want) / allowed;
        if (!(ratio <= worst)) worst = ratio, at = i;
    }
    INFO("worst |dG1| over its allowance: " << worst << " at alpha " << p.alpha[at] << ", gamma " << p.gamma[at]
                                            << ", mu " << p.mu[at] << ": " << got[at] << " against "
                                            << t.G1_up(p.alpha[at], p.gamma[at], std::abs(p.mu[at])));
    CHECK(worst <= 1.0);

    // the special values, exactly: mu = 0 gives 0, |mu| = inf gives 1
    Points s;
    for (double m : {0.0, -0.0, double(INFINITY), -double(INFINITY)}) s.add(0.01, 3.3, m);
    const std::vector<double> special = s.G1(avx2);
    CHECK(special == std::vector<double>{0.0, 0.0, 1.0, 1.0});

    // any length: each point's value is its own (a short tail runs padded through the same route)
    for (std::size_t m : {0, 1, 3, 15, 16, 17, 31, 33}) {
        std::vector<double> part(m, -1.0);
        GtrFamilyStream::get().G1_up(avx2, p.alpha.data() + 7, p.gamma.data() + 7, p.mu.data() + 7, part.data(), m);
        for (std::size_t i = 0; i < m; ++i) CHECK(part[i] == got[7 + i]);
    }
    // in place (out == mu)
    std::vector<double> in_place(p.mu.begin(), p.mu.begin() + 100);
    GtrFamilyStream::get().G1_up(avx2, p.alpha.data(), p.gamma.data(), in_place.data(), in_place.data(), 100);
    for (std::size_t i = 0; i < in_place.size(); ++i) CHECK(in_place[i] == got[i]);
}

TEST_CASE("family stream AVX2: the stated bound against independent routes, the stiff corners included", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    Points p = corners();
    std::mt19937_64 rng(46);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0),
        log_mu(std::log(1e-8), std::log(1e8));
    for (int i = 0; i < 600; ++i) p.add(std::exp(log_alpha(rng)), gamma_u(rng), std::exp(log_mu(rng)));
    // at the charts' boundary, mu = sqrt(alpha), to the last ulps on either side
    for (int i = 0; i < 40; ++i) {
        const double a = std::exp(log_alpha(rng)), g = gamma_u(rng);
        double m = std::sqrt(a);
        for (int k = 0; k < 4; ++k) m = std::nextafter(m, 0.0);
        for (int k = 0; k < 8; ++k, m = std::nextafter(m, 2.0)) p.add(a, g, m);
    }
    const std::vector<double> got = p.G1(avx2);
    double worst = 0.0;
    std::size_t at = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        const double d = std::abs(got[i] - 1.0 / (1.0 + independent(p.alpha[i], p.gamma[i], p.mu[i])));
        if (!(d <= worst)) worst = d, at = i;
    }
    INFO("worst |dG1| " << worst << " at alpha " << p.alpha[at] << ", gamma " << p.gamma[at] << ", mu " << p.mu[at]);
    WARN("family stream AVX2, " << got.size() << " points: worst |dG1| " << worst);
    CHECK(t.G1_error_bound() <= 1e-6);
    CHECK(worst <= t.G1_error_bound());
}

TEST_CASE("family stream AVX2: against the 50-digit reference", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    Points p;
    for (const auto& [alpha, gamma, mu] : {std::tuple{1e-4, 1.0 + 1e-9, 1e-3}, std::tuple{1e-4, 0.5, 1e-8},
                                           std::tuple{0.37, 2.71, 0.9}, std::tuple{1.0, 13.3, 1e8}})
        p.add(alpha, gamma, mu);
    const std::vector<double> got = p.G1(avx2);
    for (std::size_t i = 0; i < got.size(); ++i) {
        const double Lambda = 1.0 / got[i] - 1.0;  // within a few ulps of G1 of the route's Lambda
        INFO("alpha " << p.alpha[i] << ", gamma " << p.gamma[i] << ", mu " << p.mu[i] << ": G1 " << got[i]);
        const double want = static_cast<double>(ref::Lambda(ref::gtr(p.alpha[i], p.gamma[i]), p.mu[i]));
        CHECK(std::abs(got[i] - 1.0 / (1.0 + want)) <= t.G1_error_bound());
        if (want > 1e-6) CHECK(std::abs(Lambda - want) <= t.error_bound() * want + 1e-13 * (1.0 + want) * (1.0 + want));
    }
}

TEST_CASE("family stream AVX2: the same values as the AVX-512 route, where the CPU runs both", "[family]") {
    const GtrFamilyStream& stream = GtrFamilyStream::get();
    if (!stream.runs(GtrFamilyRoute::avx512) || !stream.runs(avx2)) {
        WARN("family stream: this CPU does not run both vector routes");
        return;
    }
    Points p = corners();
    std::mt19937_64 rng(47);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0), log_mu(-25.0, 25.0);
    for (int i = 0; i < 5000; ++i) p.add(std::exp(log_alpha(rng)), gamma_u(rng), std::exp(log_mu(rng)));
    const std::vector<double> a = p.G1(avx2), b = p.G1(GtrFamilyRoute::avx512);
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        worst = std::max(worst, std::abs(a[i] - b[i]) / (1e-12 * b[i] * (1.0 - b[i]) + 4.5e-16));
    INFO("worst |dG1| between the routes over its allowance: " << worst);
    CHECK(worst <= 1.0);
}
