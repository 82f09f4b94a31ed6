// The grazing law (grazing.hpp): Lambda = c/mu - 1/2 + P2(0) mu/2 below the quadrature domain, against the 50-digit
// reference (tests/reference.hpp), for built-in NDFs, a D-only NDF and a tabulated one, down to the smallest positive
// double; its refusal of an NDF with an infinite c; and `eval` answering a theta sweep to grazing.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <smithlab/gtr.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"
#include "reference.hpp"

namespace {

using ref::real;

// GGX written by hand, D alone (Walter 2007 eq. 33): smithlab reads its slopes through cos theta_m.
struct MyGgx {
    double alpha;
    double D(double c) const {
        if (c <= 0.0) return 0.0;
        const double c2 = c * c, tan2 = (1.0 - c2) / c2;
        const double s = alpha * alpha + tan2;
        return alpha * alpha / (std::numbers::pi * c2 * c2 * s * s);
    }
};

// D alone with a slope tail P22 = (1 + r^2)^(-3/2) / (2 pi): normalized, but c = 2 integral r^2 P22 dr is infinite.
struct HeavyTail {
    double D(double c) const { return c > 0.0 ? 1.0 / (2.0 * std::numbers::pi * c) : 0.0; }
};

// GGX(0.5) sampled at 0, 1, .., 85 degrees (tabulated.hpp).
smithlab::TabulatedNdf tabulated_ggx() {
    const smithlab::Ggx g = smithlab::ggx(0.5);
    std::ostringstream csv;
    csv.precision(17);
    csv << "theta_deg,D\n";
    for (int t = 0; t <= 85; ++t) csv << t << "," << g.D(std::cos(t * std::numbers::pi / 180.0)) << "\n";
    return smithlab::tabulated_ndf_from_csv(csv.str(), "ggx.csv", {true});
}

// A slope density in 50 digits read from a double one (the tabulated and D-only NDFs: the reference integrates the
// same P22 smithlab does, by its own route and arithmetic).
template <class N>
ref::SlopeDensity from_double(const N& ndf) {
    return [ndf](const real& r2) {
        const double x = static_cast<double>(r2);
        return real(x < INFINITY ? smithlab::slope_density(ndf, x) : 0.0);
    };
}

// The law's constants in 50 digits: c = 2 integral_0^inf r^2 f(r^2) dr, P2(0) = 2 integral_0^inf f(p^2) dp, by
// tanh-sinh between the breaks (the core scale; a table's rows, where its P22 has kinks) and exp-sinh beyond.
struct RefLaw {
    real c, P2_0;
};
RefLaw ref_law(const ref::SlopeDensity& f, const std::vector<double>& breaks) {
    thread_local boost::math::quadrature::tanh_sinh<real> ts(12);
    thread_local boost::math::quadrature::exp_sinh<real> es(12);
    const real tol("1e-24");
    auto both = [&](const std::function<real(const real&)>& h) {
        real sum = 0, from = 0;
        for (double b : breaks) sum += ts.integrate(h, from, real(b), tol), from = real(b);
        return 2 * (sum + es.integrate(h, from, real(INFINITY), tol));
    };
    auto cut = [](const real& r) { return r > real("1e60"); };  // as reference.cpp: the tail beyond is < 1e-60
    return {both([&](const real& r) { return cut(r) ? real(0) : r * r * f(r * r); }),
            both([&](const real& p) { return cut(p) ? real(0) : f(p * p); })};
}

// tan(theta) at the rows of tabulated_ggx(): the kinks of its P22.
std::vector<double> table_rows() {
    std::vector<double> r;
    for (int t = 1; t <= 85; ++t) r.push_back(std::tan(t * std::numbers::pi / 180.0));
    return r;
}

// One NDF under test: Lambda and G1 by a method, and its slope density in 50 digits.
struct Case {
    std::string name;
    std::function<double(double, const smithlab::LambdaOptions&)> Lambda, G1;
    ref::SlopeDensity f;
    std::vector<double> breaks;  // of the reference's quadrature: the core scale, or a table's rows
    bool smooth = true;          // P22 smooth (the law's derivation checked against the definition, ref::Lambda)
};

template <class N>
Case make_case(const std::string& name, const N& ndf, ref::SlopeDensity f, std::vector<double> breaks,
               bool smooth = true) {
    return {name,
            [ndf](double mu, const smithlab::LambdaOptions& o) { return smithlab::Lambda(ndf, mu, o); },
            [ndf](double mu, const smithlab::LambdaOptions& o) { return smithlab::G1(ndf, mu, o); },
            std::move(f),
            std::move(breaks),
            smooth};
}

std::vector<Case> cases() {
    const smithlab::NdfRegistry r = smithlab::builtin_registry();
    const smithlab::TabulatedNdf tab = tabulated_ggx();
    return {make_case("ggx(alpha=0.3)", r.make("ggx(alpha=0.3)"), ref::ggx(0.3), {0.3}),
            make_case("beckmann(alpha=0.3)", r.make("beckmann(alpha=0.3)"), ref::beckmann(0.3), {0.3}),
            make_case("gtr(alpha=0.3, gamma=0.5)", r.make("gtr(alpha=0.3, gamma=0.5)"), ref::gtr(0.3, 0.5), {0.3}),
            make_case("gtr(alpha=0.3, gamma=1)", r.make("gtr(alpha=0.3, gamma=1)"), ref::gtr(0.3, 1.0), {0.3}),
            make_case("gtr(alpha=0.3, gamma=2.5)", r.make("gtr(alpha=0.3, gamma=2.5)"), ref::gtr(0.3, 2.5), {0.3}),
            make_case("D-only GGX(0.2)", MyGgx{0.2}, ref::ggx(0.2), {0.2}),
            make_case("tabulated GGX(0.5)", tab, from_double(tab), table_rows(), false)};
}

}  // namespace

TEST_CASE("grazing law: c is E[q+], GGX alpha/2 and Beckmann alpha/(2 sqrt(pi)), and P2(0) is Walter's P2 at 0",
          "[grazing]") {
    const smithlab::GrazingLaw g = smithlab::grazing_law(smithlab::ggx(0.3));
    CHECK(g.c == Approx(0.15).epsilon(1e-13));
    CHECK(g.P2_0 == Approx(1.0 / 0.6).epsilon(1e-13));  // 1/(2 alpha)
    const smithlab::GrazingLaw b = smithlab::grazing_law(smithlab::beckmann(0.3));
    CHECK(b.c == Approx(0.3 / (2.0 * std::sqrt(std::numbers::pi))).epsilon(1e-13));
    CHECK(b.P2_0 == Approx(1.0 / (0.3 * std::sqrt(std::numbers::pi))).epsilon(1e-13));  // 1/(alpha sqrt(pi))
}

TEST_CASE("grazing law: Lambda and G1 below the quadrature domain against the 50-digit reference, down to 4.9e-324",
          "[grazing]") {
    const double tiny = std::numeric_limits<double>::denorm_min();
    double worst_law = 0.0, worst_Lambda = 0.0, worst_G1 = 0.0;  // printed for docs/accuracy-and-limits.md
    for (const Case& k : cases()) {
        const RefLaw law = ref_law(k.f, k.breaks);
        // The law itself against the definition (ref::Lambda integrates Walter's eq. 48 in r): where both are finite
        // in 50 digits, their difference is the law's truncation, O((mu/r0)^4) relative.
        for (double mu : {1e-13, 1e-20}) {
            if (!k.smooth) break;
            INFO(k.name << " mu " << mu);
            const real exact = ref::Lambda(k.f, mu), m(mu);
            const real by_law = law.c / m - real(0.5) + law.P2_0 * m / 2;
            worst_law = std::max(worst_law, ref::rel_err(static_cast<double>(by_law), exact));
            CHECK(ref::rel_err(static_cast<double>(by_law), exact) < 1e-15);
        }
        for (smithlab::Method method : {smithlab::Method::automatic, smithlab::Method::quadrature,
                                        smithlab::Method::quadrature2d, smithlab::Method::fixed}) {
            smithlab::LambdaOptions o;
            o.method = method;
            for (double mu : {1e-13, 1e-20, 1e-100, 1e-300, tiny}) {
                INFO(k.name << " method " << smithlab::to_string(method) << " mu " << mu);
                const real m(mu), Lambda_want = law.c / m - real(0.5) + law.P2_0 * m / 2;
                const real G1_want = m / (law.c + m / 2 + law.P2_0 * m * m / 2);
                const double L = k.Lambda(mu, o), G1 = k.G1(mu, o);
                if (Lambda_want > real(DBL_MAX)) {
                    CHECK(L == INFINITY);
                } else {
                    worst_Lambda = std::max(worst_Lambda, ref::rel_err(L, Lambda_want));
                    CHECK(ref::rel_err(L, Lambda_want) < 1e-11);
                }
                // G1 below DBL_MIN is a denormal: it carries fewer digits, all of them right but the last
                if (G1_want >= real(DBL_MIN)) {
                    worst_G1 = std::max(worst_G1, ref::rel_err(G1, G1_want));
                    CHECK(ref::rel_err(G1, G1_want) < 1e-11);
                } else {
                    CHECK(std::abs(G1 - static_cast<double>(G1_want)) <= tiny);
                }
                CHECK(G1 > 0.0);
                // mu < 0 follows the convention; mu = 0 stays exact
                CHECK(k.Lambda(-mu, o) == -1.0 - L);
            }
            CHECK(k.Lambda(0.0, o) == INFINITY);
            CHECK(k.G1(0.0, o) == 0.0);
        }
    }
    std::printf("grazing law: truncation against the definition %.2g; Lambda %.2g, G1 %.2g against the 50-digit law\n",
                worst_law, worst_Lambda, worst_G1);
}

TEST_CASE("grazing law: the quadrature routes still answer themselves inside their domain", "[grazing]") {
    // At mu = 1e-12 (the domain's end for r0 <= 1) the route, not the law, answers: a different number in the last
    // digits, and the Lambda_1d call itself still refuses below.
    const smithlab::Gtr g = smithlab::gtr(0.3, 1.5);
    smithlab::LambdaOptions q;
    q.method = smithlab::Method::quadrature;
    CHECK(smithlab::Lambda(g, 1e-12, q) == smithlab::Lambda_1d(g, 1e-12));
    CHECK_THROWS_AS(smithlab::Lambda_1d(g, 1e-13), smithlab::input_error);
    // GGX(1e49): its domain starts at mu = 1e37; mu = 0.5 is answered by the law (Lambda = alpha / (2 mu) = 1e49)
    const smithlab::Ggx big = smithlab::ggx(1e49);
    CHECK(smithlab::Lambda(big, 0.5, q) == Approx(1e49).epsilon(1e-12));
    // GGX(1e-10): the law answers at mu <= 1e-8 r0 = 1e-18; between that and 1e-12 neither it nor the quadrature
    // holds, and the quadrature refuses.
    const smithlab::Ggx thin = smithlab::ggx(1e-10);
    CHECK(smithlab::Lambda(thin, 1e-19, q) == Approx(thin.Lambda(1e-19)).epsilon(1e-12));
    CHECK_THROWS_AS(smithlab::Lambda(thin, 1e-15, q), smithlab::input_error);
}

TEST_CASE("grazing law: an NDF whose c is infinite is refused, and the message says why", "[grazing]") {
    CHECK_THROWS_WITH(smithlab::grazing_law(HeavyTail{}),
                      Catch::Contains("no grazing law") && Catch::Contains("r^-3.05") && Catch::Contains("infinite"));
    CHECK_THROWS_AS(smithlab::Lambda(HeavyTail{}, 1e-13), smithlab::input_error);
    CHECK_THROWS_AS(smithlab::G1(HeavyTail{}, 1e-300), smithlab::input_error);
}

TEST_CASE("eval: a theta sweep and CSV rows reaching grazing answer every point", "[grazing][cli]") {
    // The sweep's points near 90 degrees have mu = cot(theta) ~ 1e-15 .. 0: below the quadrature domain.
    for (const char* method : {"auto", "quadrature", "quadrature2d", "fixed"}) {
        INFO(method);
        const smithlab_test::Run r =
            smithlab_test::run(std::string("eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --method ") + method +
                               " --theta-range 89.9999999999999:90:4");
        CHECK(r.rc == 0);
        CHECK(r.err.empty());
        CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 5);  // the header and 4 rows
    }
    const std::string rows = (smithlab_test::scratch() / "grazing_rows.csv").string();
    smithlab_test::write(rows, "ndf,mu\n\"beckmann(alpha=0.3)\",6.123233995736766e-17\n\"blinn(n=20)\",1e-300\n");
    const smithlab_test::Run csv = smithlab_test::run("eval --input '" + rows + "'");
    CHECK(csv.rc == 0);
    CHECK(csv.err.empty());
    // One point prints what answered.
    const smithlab_test::Run one =
        smithlab_test::run("eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --mu 6.123233995736766e-17");
    CHECK(one.rc == 0);
    CHECK(one.out.find("method  auto (grazing law") != std::string::npos);
    // G1 where Lambda overflows: mu / c = 4.9e-324 / 0.15, a denormal (7 x 4.9e-324), not 0.
    const smithlab_test::Run below = smithlab_test::run("eval --ndf 'ggx(alpha=0.3)' --mu 4.9e-324");
    CHECK(below.rc == 0);
    CHECK(below.out.find("lambda  inf\ng1      3.4584595208887258e-323\n") != std::string::npos);
}

TEST_CASE("the family evaluator's refusal names the parameter, its value and the domain", "[grazing][variants]") {
    const smithlab::NdfRegistry nr = smithlab::builtin_registry();
    const smithlab::VariantRegistry vr = smithlab::builtin_variants();
    const smithlab::LambdaVariant& family = vr.at("family");
    CHECK_THROWS_WITH(smithlab::prepare(family, nr.make("gtr(alpha=0.3, gamma=21)")),
                      "method 'family' covers gtr with alpha in [1e-4, 1] and gamma in [0, 20]; got gamma = 21");
    CHECK_THROWS_WITH(smithlab::prepare(family, nr.make("gtr(alpha=5e-5, gamma=1)")),
                      Catch::EndsWith("; got alpha = 5e-05"));
    CHECK_THROWS_WITH(smithlab::prepare(family, nr.make("ggx(alpha=0.3)")), Catch::EndsWith("; got a 'ggx' ndf"));
}
