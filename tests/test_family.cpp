// The GTR family evaluator (gtr/family.hpp): two charts of polynomial patches for every (alpha, gamma), against routes
// it is not built from (the adaptive 1D quadrature, Boost tanh-sinh, where its knots come from trapezoid strips; the
// closed forms; the 50-digit reference), its stated bound checked as a bound in every leaf, and its input rules.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <smithlab/gtr.hpp>
#include <smithlab/gtr/family.hpp>
#include <smithlab/gtr/family_stream.hpp>
#include <thread>
#include <vector>

#include "reference.hpp"

using namespace smithlab;

namespace {

// An independent Lambda: the closed form at integer gamma, else the adaptive tanh-sinh route (the tree's knots are
// trapezoid strips).
double independent(double alpha, double gamma, double mu) {
    const Gtr n = gtr(alpha, gamma);
    return gtr_has_closed_form(gamma) ? n.Lambda(mu) : Lambda_1d(n, mu, {Backend::boost, 1e-12});
}

struct Worst {
    double rel = 0.0, dG1 = 0.0, alpha = 0.0, gamma = 0.0, mu = 0.0;
    void add(double got, double want, double a, double g, double m) {
        const double r = std::abs(got - want) / want;
        if (r > rel) rel = r, alpha = a, gamma = g, mu = m;
        dG1 = std::max(dG1, std::abs(1.0 / (1.0 + got) - 1.0 / (1.0 + want)));
    }
};

}  // namespace

TEST_CASE("family: the stated bound holds on random points over the whole domain", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    const GtrFamilyData& d = t.data();
    WARN("family trees: " << d.n_leaves << " leaves of degree " << GtrFamily::degree << ", " << t.bytes() / 1e6
                          << " MB, depth <= " << d.max_depth << "; stated bounds " << t.error_bound()
                          << " (relative dLambda), " << t.G1_error_bound() << " (|dG1|)");
    CHECK(t.error_bound() <= 1e-5);  // the stated targets
    CHECK(t.G1_error_bound() <= 1e-6);
    std::mt19937_64 rng(14);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0), gamma_low(0.0, 3.0),
        log_mu(std::log(1e-8), std::log(1e8));
    Worst w;
    for (int i = 0; i < 3000; ++i) {
        const double alpha = std::exp(log_alpha(rng)), gamma = i % 3 == 0 ? gamma_low(rng) : gamma_u(rng);
        const double mu = std::exp(log_mu(rng));
        w.add(t.Lambda_up(alpha, gamma, mu), independent(alpha, gamma, mu), alpha, gamma, mu);
    }
    INFO("worst relative dLambda " << w.rel << " at alpha " << w.alpha << ", gamma " << w.gamma << ", mu " << w.mu
                                   << "; worst |dG1| " << w.dG1);
    WARN("family, random points: worst relative dLambda " << w.rel << ", |dG1| " << w.dG1);
    CHECK(w.rel <= t.error_bound());
    CHECK(w.dG1 <= t.G1_error_bound());
}

TEST_CASE("family: the stiff corners, mu = 1e-8 .. 1e8, 0 and inf", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    Worst w;
    for (double alpha : {1e-4, 1.5e-4, 0.999999, 1.0})
        for (double gamma : {0.0, 1e-9, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 1.5, 2.0, 19.99, 20.0})
            for (double mu : {1e-8, 3e-7, 1e-4, 0.01, 1.0, 3.0, 1e4, 1e8}) {
                w.add(t.Lambda_up(alpha, gamma, mu), independent(alpha, gamma, mu), alpha, gamma, mu);
                CHECK(G1_gtr_family(alpha, gamma, 0.0) == 0.0);
                CHECK(Lambda_gtr_family(alpha, gamma, INFINITY) == 0.0);
                CHECK(Lambda_gtr_family(alpha, gamma, 0.0) == INFINITY);
            }
    INFO("worst relative dLambda " << w.rel << " at alpha " << w.alpha << ", gamma " << w.gamma << ", mu " << w.mu);
    CHECK(w.rel <= t.error_bound());
    CHECK(w.dG1 <= t.G1_error_bound());
    // beyond the charts (xi < xi_lo, eta > eta_hi): the asymptotes, finite and positive to the ends of double
    // (Lambda ~ C mu^-2 underflows to 0 near mu = 1e300)
    for (double mu : {1e-300, 1e-20, 1e20}) {
        const double L = t.Lambda_up(1e-4, 1.5, mu);
        CHECK((L > 0.0 && L < INFINITY));
    }
    CHECK(t.Lambda_up(1e-4, 1.5, 1e300) == 0.0);
    CHECK(t.Lambda_up(1e-4, 1.5, 5e-324) == INFINITY);
}

TEST_CASE("family: the report's grid (9 alpha x 17 mu x 14 gamma)", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    Worst w;
    for (int i = 0; i < 9; ++i)
        for (double gamma : {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 5.5, 7.0, 10.0, 15.0, 20.0})
            for (int k = 0; k < 17; ++k) {
                const double alpha = std::pow(10.0, -4.0 + 0.5 * i), mu = std::pow(10.0, -4.0 + 0.5 * k);
                w.add(t.Lambda_up(alpha, gamma, mu), independent(alpha, gamma, mu), alpha, gamma, mu);
            }
    INFO("worst relative dLambda " << w.rel << " at alpha " << w.alpha << ", gamma " << w.gamma << ", mu " << w.mu);
    WARN("family, report grid: worst relative dLambda " << w.rel << ", |dG1| " << w.dG1);
    CHECK(w.rel <= t.error_bound());
    CHECK(w.dG1 <= t.G1_error_bound());
}

TEST_CASE("family: against the 50-digit reference", "[family][slow]") {
    const GtrFamily& t = GtrFamily::get();
    for (const auto& [alpha, gamma, mu] : {std::tuple{1e-4, 1.0 + 1e-9, 1e-3}, std::tuple{1e-4, 0.5, 1e-8},
                                           std::tuple{0.37, 2.71, 0.9}, std::tuple{1.0, 13.3, 1e8}}) {
        const double got = t.Lambda_up(alpha, gamma, mu);
        INFO("alpha " << alpha << ", gamma " << gamma << ", mu " << mu << ": " << got);
        CHECK(ref::close(got, ref::Lambda(ref::gtr(alpha, gamma), mu), t.error_bound()));
    }
}

TEST_CASE("family: input rules and conventions", "[family]") {
    auto says = [](auto f, const char* what) {
        try {
            f();
        } catch (const input_error& e) {
            return std::string(e.what()).find(what) != std::string::npos;
        }
        return false;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(says([] { Lambda_gtr_family(0.0, 1.0, 0.5); }, "alpha"));
    CHECK(says([] { Lambda_gtr_family(9e-5, 1.0, 0.5); }, "alpha"));
    CHECK(says([] { Lambda_gtr_family(1.0000001, 1.0, 0.5); }, "alpha"));
    CHECK(says([&] { Lambda_gtr_family(nan, 1.0, 0.5); }, "alpha"));
    CHECK(says([] { Lambda_gtr_family(0.5, -1e-12, 0.5); }, "gamma"));
    CHECK(says([] { Lambda_gtr_family(0.5, 20.000001, 0.5); }, "gamma"));
    CHECK(says([&] { G1_gtr_family(0.5, nan, 0.5); }, "gamma"));
    CHECK(says([&] { Lambda_gtr_family(0.5, 1.0, nan); }, "mu is NaN"));
    const double L = Lambda_gtr_family(0.3, 1.7, 0.6);
    CHECK(Lambda_gtr_family(0.3, 1.7, -0.6) == -1.0 - L);                        // Smith's downward convention
    CHECK(Lambda_gtr_family(0.3, 1.7, -0.6, Downward::hammon_symmetric) == -L);  // Hammon's
    CHECK(G1_gtr_family(0.3, 1.7, -0.6) == 1.0 / (1.0 + L));                     // G1 takes |mu|

    // The variant: GTR in the domain only; through the variant interface, the same numbers.
    const VariantRegistry vr = builtin_variants();
    const LambdaVariant& v = vr.at("family");
    const NdfRegistry nr = builtin_registry();
    CHECK(v.applies(nr.make("gtr(alpha=0.3, gamma=1.7)")));
    CHECK_FALSE(v.applies(nr.make("gtr(alpha=1e-5, gamma=1.7)")));
    CHECK_FALSE(v.applies(nr.make("gtr(alpha=0.3, gamma=21)")));
    CHECK_FALSE(v.applies(nr.make("ggx(alpha=0.3)")));
    CHECK(prepare(v, nr.make("gtr(alpha=0.3, gamma=1.7)"))(0.6) == L);
}

TEST_CASE("family: one evaluator, shared by every thread", "[family]") {
    const GtrFamily* seen[2] = {nullptr, nullptr};
    double got[2] = {0.0, 0.0};
    std::thread a([&] {
        seen[0] = &GtrFamily::get();
        got[0] = seen[0]->Lambda_up(0.2, 2.5, 0.3);
    });
    std::thread b([&] {
        seen[1] = &GtrFamily::get();
        got[1] = seen[1]->Lambda_up(0.2, 2.5, 0.3);
    });
    a.join();
    b.join();
    CHECK(seen[0] == seen[1]);
    CHECK(got[0] == got[1]);
}

TEST_CASE("family: the stated bound holds at two random points of every leaf", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    const GtrFamilyData& d = t.data();
    std::mt19937_64 rng(22);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Worst w;
    int unreached = 0, through_Lambda_up = 0;
    for (std::size_t leaf = 0; leaf < d.n_leaves; ++leaf) {
        const GtrFamilyLeaf& box = d.leaves[leaf];  // s = (x - centre) * scale in [-1, 1]
        const std::array<double, 3> centre = {box.centre[0], box.centre[1], box.centre[2]};
        const bool in0 = t.locate(0, centre).leaf == &box, in1 = t.locate(1, centre).leaf == &box;
        unreached += !in0 && !in1;  // each leaf is found from its own centre, in its chart
        const int chart = in0 ? 0 : 1;
        for (int k = 0; k < 2; ++k) {  // anywhere in the box, across the charts' boundary too: the leaf's own value
            const std::array<double, 3> s = {u(rng), u(rng), u(rng)};
            const double a = box.centre[0] + s[0] / box.scale[0], gamma = box.centre[1] + s[1] / box.scale[1],
                         z = box.centre[2] + s[2] / box.scale[2];
            const double alpha = std::min(1.0, std::exp(a)), mu = std::exp(GtrFamily::ln_mu_of(chart, a, z));
            const double want = independent(alpha, gamma, mu);
            w.add(std::exp(GtrFamily::polynomial(box, s)) / mu, want, alpha, gamma, mu);
            // on the leaf's own side of the boundary, the whole call (chart, locate, polynomial, exp) as well
            if (GtrFamily::chart_of(std::log(alpha), std::log(mu)) == chart) {
                w.add(t.Lambda_up(alpha, gamma, mu), want, alpha, gamma, mu);
                ++through_Lambda_up;
            }
        }
    }
    CHECK(unreached == 0);
    CHECK(through_Lambda_up > static_cast<int>(d.n_leaves));  // most of the points (a box straddles rarely)
    INFO("worst relative dLambda " << w.rel << " at alpha " << w.alpha << ", gamma " << w.gamma << ", mu " << w.mu
                                   << "; worst |dG1| " << w.dG1);
    WARN("family, two random points per leaf (" << d.n_leaves << " leaves): worst relative dLambda " << w.rel
                                                << ", |dG1| " << w.dG1);
    CHECK(w.rel <= t.error_bound());
    CHECK(w.dG1 <= t.G1_error_bound());
}

TEST_CASE("family: every point lands in its leaf's box", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0), log_mu(-25.0, 25.0);
    int outside = 0, empty = 0;
    auto land = [&](double alpha, double gamma, double mu) {
        const double a = std::log(alpha), eta = std::log(mu);
        const int chart = GtrFamily::chart_of(a, eta);  // as Lambda_up
        const GtrFamily::Located leaf = t.locate(chart, {a, gamma, GtrFamily::z_of(chart, a, eta)});
        for (double s : leaf.s) outside += !(std::abs(s) <= 1.0 + 1e-12);
        empty += leaf.leaf == &t.data().leaves[t.data().n_leaves];  // the empty leaf: a box in the other chart's half
    };
    for (int i = 0; i < 100000; ++i)
        land(std::exp(log_alpha(rng)), i % 100 == 0 ? 20.0 * (i % 200 == 0) : gamma_u(rng), std::exp(log_mu(rng)));
    // at the charts' boundary, mu = sqrt(alpha), to the last ulp on either side
    for (int i = 0; i < 2000; ++i) {
        const double alpha = i == 0 ? 1e-4 : i == 1 ? 1.0 : std::exp(log_alpha(rng)), gamma = gamma_u(rng);
        double mu = std::sqrt(alpha);
        for (int k = 0; k < 4; ++k) mu = std::nextafter(mu, 0.0);
        for (int k = 0; k < 8; ++k, mu = std::nextafter(mu, 2.0)) land(alpha, gamma, mu);
    }
    CHECK(outside == 0);
    CHECK(empty == 0);
}

// The stream route (family_stream.hpp): the same leaves by another route (eight lanes, libmvec's logs, a uniform grid
// per top box instead of the descent), so the same G1 to rounding: |dG1| <= 1e-12 G1 (1 - G1) (relative dLambda
// <= 1e-12) plus two ulps of 1; the special values exactly. Within a few ulps of the charts' boundary the two routes'
// logs may pick different charts, whose leaves both hold there: checked against the independent route instead.
TEST_CASE("family stream: the same G1 as one point at a time, over the whole domain and its corners", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    const GtrFamilyStream& stream = GtrFamilyStream::get();
    WARN("family stream: " << (stream.vectorized() ? "eight lanes (AVX-512)" : "one point at a time (no AVX-512)"));
    std::vector<double> alpha, gamma, mu;
    auto add = [&](double a, double g, double m) { alpha.push_back(a), gamma.push_back(g), mu.push_back(m); };
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0), gamma_low(0.0, 3.0),
        log_mu(-25.0, 25.0);
    for (int i = 0; i < 20000; ++i)
        add(std::exp(log_alpha(rng)), i % 3 == 0 ? gamma_low(rng) : gamma_u(rng), std::exp(log_mu(rng)));
    for (double a : {1e-4, 1.5e-4, 0.999999, 1.0})
        for (double g : {0.0, 1e-9, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 1.5, 2.0, 19.99, 20.0})
            for (double m : {0.0, 5e-324, 1e-300, 1e-8, 1e-4, 1.0, 1e4, 1e8, 1e300, double(INFINITY)}) add(a, g, m);
    const std::size_t n = mu.size();
    std::vector<double> got(n);
    stream.G1_up(alpha.data(), gamma.data(), mu.data(), got.data(), n);
    double worst = 0.0;
    std::size_t at = 0;
    int special = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double want = t.G1_up(alpha[i], gamma[i], mu[i]);
        if (mu[i] == 0.0 || mu[i] == INFINITY) {
            special += got[i] == (mu[i] == 0.0 ? 0.0 : 1.0);
            continue;
        }
        const double allowed = 1e-12 * want * (1.0 - want) + 4.5e-16, ratio = std::abs(got[i] - want) / allowed;
        if (ratio > worst) worst = ratio, at = i;
    }
    INFO("worst |dG1| over its allowance: " << worst << " at alpha " << alpha[at] << ", gamma " << gamma[at] << ", mu "
                                            << mu[at] << ": " << got[at] << " against "
                                            << t.G1_up(alpha[at], gamma[at], mu[at]));
    CHECK(worst <= 1.0);
    CHECK(special == 4 * 9 * 2);

    // any length: each point's value is its own (a short tail runs padded through the same route)
    for (std::size_t m : {0, 1, 15, 16, 17, 31, 33}) {
        std::vector<double> part(m, -1.0);
        stream.G1_up(alpha.data() + 5, gamma.data() + 5, mu.data() + 5, part.data(), m);
        for (std::size_t i = 0; i < m; ++i) CHECK(part[i] == got[5 + i]);
    }
    // at the charts' boundary, mu = sqrt(alpha), to the last ulp on either side: the stated bound
    Worst w;
    std::vector<double> a8(8), g8(8), m8(8), out8(8);
    for (int i = 0; i < 300; ++i) {
        const double a = std::exp(log_alpha(rng)), g = gamma_u(rng);
        double m = std::sqrt(a);
        for (int k = 0; k < 4; ++k) m = std::nextafter(m, 0.0);
        for (int k = 0; k < 8; ++k, m = std::nextafter(m, 2.0)) a8[k] = a, g8[k] = g, m8[k] = m;
        stream.G1_up(a8.data(), g8.data(), m8.data(), out8.data(), 8);
        const double want = 1.0 / (1.0 + independent(a, g, std::sqrt(a)));
        for (double o : out8) w.dG1 = std::max(w.dG1, std::abs(o - want));
    }
    INFO("at the charts' boundary: worst |dG1| " << w.dG1);
    CHECK(w.dG1 <= t.G1_error_bound());

    // in place (out == mu)
    std::vector<double> in_place(mu.begin(), mu.begin() + 100);
    stream.G1_up(alpha.data(), gamma.data(), in_place.data(), in_place.data(), in_place.size());
    for (std::size_t i = 0; i < in_place.size(); ++i) CHECK(in_place[i] == got[i]);
}

// The stream's two data structures by themselves (built only where the stream runs on eight lanes): the grid of each
// top box gives a leaf whose box holds the point (the tree's own, away from edges), and each leaf's terms in lanes sum
// to the leaf's polynomial (family.hpp's, in its stored order).
TEST_CASE("family stream: its grids find the tree's leaves, its lanes hold their polynomials", "[family]") {
    const GtrFamilyStream& stream = GtrFamilyStream::get();
    if (!stream.vectorized()) {
        WARN("family stream: no AVX-512 here, its layout is not built");
        return;
    }
    const GtrFamily& t = GtrFamily::get();
    const GtrFamilyData& d = t.data();
    std::mt19937_64 rng(44);
    std::uniform_real_distribution<double> u(0.0, 1.0), sym(-1.0, 1.0);
    int other = 0, outside = 0;
    for (int n = 0; n < 50000; ++n) {
        const int c = n % 2;
        std::array<double, 3> x;
        for (int a = 0; a < 3; ++a) x[a] = GtrFamily::lo[c][a] + (GtrFamily::hi[c][a] - GtrFamily::lo[c][a]) * u(rng);
        // the kernel's index, in scalar code
        double tt[3];
        int top[3], cell = 0;
        for (int a = 0; a < 3; ++a) {
            tt[a] = (x[a] - GtrFamily::lo[c][a]) * GtrFamily::inv_step(c, a);
            top[a] = std::min(static_cast<int>(tt[a]), GtrFamily::top[a] - 1);
            cell = cell * GtrFamily::top[a] + top[a];
        }
        const GtrFamilyStream::Cell& box = stream.cells()[c * GtrFamily::top_cells + cell];
        int fine = 0;
        for (int a = 0; a < 3; ++a) {
            const int cells = 1 << box.depth[a];
            fine = (fine << box.depth[a]) + std::min(static_cast<int>((tt[a] - top[a]) * cells), cells - 1);
        }
        const std::size_t id = stream.ids()[box.offset + fine];
        const GtrFamily::Located tree = t.locate(c, x);
        other += id != static_cast<std::size_t>(tree.leaf - d.leaves);
        if (id < d.n_leaves)
            for (int a = 0; a < 3; ++a)
                outside += !(std::abs((x[a] - d.leaves[id].centre[a]) * d.leaves[id].scale[a]) <= 1.0 + 1e-12);
    }
    CHECK(other == 0);
    CHECK(outside == 0);

    const GtrFamilyStream::Lanes& lanes = stream.lanes();
    double worst = 0.0;
    for (int n = 0; n < 5000; ++n) {
        const std::size_t leaf = rng() % d.n_leaves;
        const std::array<double, 3> s3 = {sym(rng), sym(rng), sym(rng)};
        const GtrFamilyStream::Leaf& l = stream.leaves()[leaf];
        double sum = l.c0 + l.linear[0] * s3[0] + l.linear[1] * s3[1] + l.linear[2] * s3[2];
        for (int g = 0; g < 4; ++g)
            for (int lane = 0; lane < 8; ++lane) {
                double h = 0.0;
                for (int k = GtrFamilyStream::Lanes::steps[g] - 1; k >= 0; --k)
                    h = h * s3[2] + l.c[GtrFamilyStream::Lanes::offset[g] + 8 * k + lane];
                sum += h * std::pow(s3[0], lanes.i[g][lane]) * std::pow(s3[1], lanes.j[g][lane]) *
                    std::pow(s3[2], lanes.k0[g][lane]);
            }
        const double want = GtrFamily::polynomial(d.leaves[leaf], s3);
        worst = std::max(worst, std::abs(sum - want) / (1.0 + std::abs(want)));
    }
    INFO("worst difference of the lanes' sum from the leaf's polynomial: " << worst);
    CHECK(worst <= 1e-13);
}

TEST_CASE("family stream: the stated bound against independent routes", "[family]") {
    const GtrFamily& t = GtrFamily::get();
    std::mt19937_64 rng(43);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0),
        log_mu(std::log(1e-8), std::log(1e8));
    std::vector<double> alpha, gamma, mu;
    for (int i = 0; i < 400; ++i)
        alpha.push_back(std::exp(log_alpha(rng))), gamma.push_back(gamma_u(rng)), mu.push_back(std::exp(log_mu(rng)));
    std::vector<double> got(mu.size());
    G1_gtr_family(alpha, gamma, mu, got);
    double worst = 0.0;
    for (std::size_t i = 0; i < mu.size(); ++i)
        worst = std::max(worst, std::abs(got[i] - 1.0 / (1.0 + independent(alpha[i], gamma[i], mu[i]))));
    WARN("family stream, 400 random points: worst |dG1| " << worst);
    CHECK(worst <= t.G1_error_bound());
}

TEST_CASE("family stream: input rules (nothing written on bad input)", "[family]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> alpha(20, 0.3), gamma(20, 1.7), mu(20, 0.6), out(20, -7.0);
    auto says = [&](const char* what) {
        try {
            G1_gtr_family(alpha, gamma, mu, out);
        } catch (const input_error& e) {
            const bool named = std::string(e.what()).find(what) != std::string::npos;
            INFO(e.what());
            CHECK(named);
            for (double o : out) CHECK(o == -7.0);
            return named;
        }
        return false;
    };
    alpha[5] = nan;
    CHECK(says("family: alpha[5] must be in [1e-4, 1]"));
    alpha[5] = 0.3, gamma[2] = 21.0;
    CHECK(says("family: gamma[2] must be in [0, 20]"));
    gamma[2] = 1.7, mu[19] = nan;
    CHECK(says("family: mu[19] is NaN"));
    mu[19] = 0.6;
    std::vector<double> short_out(19);
    CHECK_THROWS_AS(G1_gtr_family(alpha, gamma, mu, short_out), input_error);
    // G1 takes |mu|, as G1_gtr_family at one point
    mu[3] = -0.6;
    G1_gtr_family(alpha, gamma, mu, out);
    for (double o : out) CHECK(o == out[0]);
    CHECK(std::abs(out[0] - G1_gtr_family(0.3, 1.7, 0.6)) <= 1e-13);
}
