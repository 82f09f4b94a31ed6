// The eval estimators (walk.hpp, EvalEstimator) against each other and against closed forms: expected_first and
// reciprocal agree with next_event within a few standard errors (independent walks) at points, NDFs and facets of
// every kind, order by order; expected_first's first hit on mirror facets is the closed-form single scattering of GGX
// exactly (no variance left); their cells are the same bits at 1 and 2 threads.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <smithlab/fit/dataset.hpp>
#include <smithlab/gtr.hpp>
#include <smithlab/walk/trace.hpp>
#include <string>

#include "estimates.hpp"

namespace {

namespace walk = smithlab::walk;
using smithlab::Vec3;
using smithlab_test::sigmas;
using walk::EvalEstimator;

template <class N, class M>
void check_agreement(const std::string& name, const N& ndf, const M& material, std::int64_t walks) {
    const walk::Microsurface ms(ndf);
    struct Point {
        double ti, to, phi;
    };
    int cell = 0;
    for (const Point p : {Point{45, 60, 135}, {0, 40, 0}, {60, 60, 180}, {80, 85, 0}, {15, 85, 90}, {30, 30, 180}}) {
        walk::EvalRequest r{.wi = smithlab::direction_from_deg(p.ti, 0.0),
                            .wo = smithlab::direction_from_deg(p.to, p.phi),
                            .cell = static_cast<std::uint64_t>(cell++),
                            .walks = walks};
        r.seed = 11;
        const walk::EvalTally old = walk::eval_cell(ms, material, r);
        for (const EvalEstimator e : {EvalEstimator::expected_first, EvalEstimator::reciprocal}) {
            r.seed = 12;  // independent walks
            r.estimator = e;
            const walk::EvalTally now = walk::eval_cell(ms, material, r);
            INFO(name << " at (" << p.ti << ", " << p.to << ", " << p.phi << "): next_event " << old.value().value
                      << " +- " << old.value().stderr_ << ", "
                      << (e == EvalEstimator::reciprocal ? "reciprocal " : "expected_first ") << now.value().value
                      << " +- " << now.value().stderr_);
            REQUIRE(old.value().value > 0.0);
            CHECK(sigmas(old.value(), now.value()) < 4.5);
            // Order by order too: neither the first hit's closed form nor the reversal may move energy between orders.
            for (int b = 0; b < walk::order_bins; ++b) {
                const walk::Estimate o = estimate(old.orders[b], old.walks), n = estimate(now.orders[b], now.walks);
                INFO("order bin " << b + 1 << ": " << o.value << " +- " << o.stderr_ << " against " << n.value << " +- "
                                  << n.stderr_);
                if (o.stderr_ + n.stderr_ > 0.0) CHECK(sigmas(o, n) < 4.5);
            }
        }
    }
}

}  // namespace

TEST_CASE("eval estimators: expected_first and reciprocal agree with next_event", "[walk][eval]") {
    check_agreement("ggx(0.5) fresnel-diffuse", smithlab::ggx(0.5), walk::FresnelDiffuse{0.04, 1.0}, 60'000);
    check_agreement("ggx(0.5) lambert", smithlab::ggx(0.5), walk::Lambert{0.8}, 60'000);
    check_agreement("ggx(0.3) mirror", smithlab::ggx(0.3), walk::Mirror{}, 60'000);
    check_agreement("ggx(0.5) dielectric", smithlab::ggx(0.5), walk::Dielectric{1.5}, 40'000);
    check_agreement("gtr(0.5, 1) fresnel-diffuse", smithlab::gtr(0.5, 1.0), walk::FresnelDiffuse{0.04, 1.0}, 20'000);
    check_agreement("gtr(0.7, 3) lambert", smithlab::gtr(0.7, 3.0), walk::Lambert{1.0}, 20'000);
    check_agreement("D-only ggx(0.5) fresnel-diffuse", smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(0.5)},
                    walk::FresnelDiffuse{0.04, 1.0}, 20'000);
}

TEST_CASE("eval estimators: expected_first's first hit on mirrors is GGX's single scattering exactly", "[walk][eval]") {
    // f1(wi, wo) cos theta_o = D(h) G2(wi, wo) / (4 cos theta_i), G2 = 1 / (1 + Lambda(wi) + Lambda(wo)) (the
    // height-correlated Smith G2), GGX's D (Walter et al. 2007, eq. 33) and Lambda (Heitz 2014, eq. 72) written out
    // here.
    const double alpha = 0.4;
    const walk::Microsurface ms(smithlab::ggx(alpha));
    const auto Lambda = [&](const Vec3& w) {
        const double t2 = (1.0 - w.z() * w.z()) / (w.z() * w.z());
        return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * t2));
    };
    const auto D = [&](const Vec3& m) {
        const double c2 = m.z() * m.z(), t2 = (1.0 - c2) / c2, a2 = alpha * alpha;
        return a2 / (std::numbers::pi * c2 * c2 * (a2 + t2) * (a2 + t2));
    };
    for (const auto& [ti, to, phi] : {std::tuple{30.0, 50.0, 180.0}, {70.0, 20.0, 90.0}, {85.0, 80.0, 0.0}}) {
        const Vec3 wi = smithlab::direction_from_deg(ti, 0.0), wo = smithlab::direction_from_deg(to, phi);
        const Vec3 h = (wi + wo).normalized();
        const double expected = D(h) / (4.0 * wi.z() * (1.0 + Lambda(wi) + Lambda(wo)));
        for (std::uint64_t k = 0; k < 50; ++k) {
            smithlab::WalkRng g(3, 0, k);
            const walk::EvalSample s =
                walk::eval_walk(ms, walk::Mirror{}, wi, wo, g, {.max_order = 1}, EvalEstimator::expected_first);
            INFO("(" << ti << ", " << to << ", " << phi << ") walk " << k);
            CHECK(s.specular[0] == Approx(expected).epsilon(1e-10));
        }
    }
}

TEST_CASE("eval estimators: expected_first and reciprocal cells are the same bits at 1 and 2 threads", "[walk][eval]") {
    const walk::Microsurface ms(smithlab::gtr(0.5, 3.0));
    for (const EvalEstimator e : {EvalEstimator::expected_first, EvalEstimator::reciprocal}) {
        walk::EvalRequest r{.wi = smithlab::direction_from_deg(30.0, 0.0),
                            .wo = smithlab::direction_from_deg(75.0, 135.0),
                            .walks = 9000,
                            .block = 1000};
        r.estimator = e;
        r.threads = 1;
        const walk::EvalTally one = walk::eval_cell(ms, walk::FresnelDiffuse{0.04, 1.0}, r);
        r.threads = 2;
        const walk::EvalTally two = walk::eval_cell(ms, walk::FresnelDiffuse{0.04, 1.0}, r);
        CHECK(one.value().value == two.value().value);
        CHECK(one.value().stderr_ == two.value().stderr_);
        CHECK(one.events == two.events);
        // And it is another estimator than next_event: the same walks' random numbers give other values.
        r.estimator = EvalEstimator::next_event;
        CHECK(walk::eval_cell(ms, walk::FresnelDiffuse{0.04, 1.0}, r).value().value != one.value().value);
    }
}

TEST_CASE("eval estimators: the fitter's point traces by reciprocal", "[walk][eval][fit]") {
    // trace_eval_point's default is the estimator with the lowest equal-error time (bench_fit): the same sums as the
    // walks of eval_walk by reciprocal, and other sums than next_event's.
    const walk::Microsurface ms(smithlab::ggx(0.5));
    const walk::FresnelDiffuse material{0.04, 1.0};
    const Vec3 wi = smithlab::direction_from_deg(20.0, 0.0), wo = smithlab::direction_from_deg(80.0, 90.0);
    const smithlab::fit::SplitMoments m = smithlab::fit::trace_eval_point(ms, material, wi, wo, 5, 2, 500);
    double by_hand = 0.0;
    for (std::uint64_t k = 0; k < 500; ++k) {
        smithlab::WalkRng g(5, 2, k);
        by_hand += walk::eval_walk(ms, material, wi, wo, g, {}, EvalEstimator::reciprocal).by_diffuse[1];
    }
    CHECK(m.sum[1] == by_hand);
    const smithlab::fit::SplitMoments old =
        smithlab::fit::trace_eval_point(ms, material, wi, wo, 5, 2, 500, EvalEstimator::next_event);
    CHECK(old.sum[1] != m.sum[1]);
}
