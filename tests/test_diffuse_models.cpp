// The diffuse models (fit/diffuse_models.hpp), each against something independent of its code: the
// symmetry every BRDF owes, limits derived by hand (Lambert at zero roughness), values derived by hand from the
// papers' formulas at convenient angles, and hemisphere integrals by a 2D Gauss-Legendre rule written here.
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <regex>
#include <span>
#include <string>
#include <vector>

#include "smithlab/errors.hpp"
#include "smithlab/fit/diffuse_models.hpp"
#include "smithlab/fit/glsl.hpp"
#include "smithlab/geometry.hpp"

using namespace smithlab;
using namespace smithlab::fit;

namespace {

constexpr double pi = std::numbers::pi;

// n-point Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from Chebyshev guesses; Golub-Welsch would do
// as well): exact for polynomials of degree 2n - 1.
struct Rule {
    std::vector<double> x, w;
};
Rule gauss_legendre(int n) {
    Rule r{std::vector<double>(n), std::vector<double>(n)};
    for (int i = 0; i < n; ++i) {
        double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = z;  // P_0, P_1, then the recurrence up to P_n
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            if (n == 1) p0 = 1.0;
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            const double dz = p1 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        r.x[i] = z;
        r.w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    return r;
}

// The integral of g over [a, b] by the rule.
template <class G>
double integrate(const Rule& r, double a, double b, G&& g) {
    const double h = 0.5 * (b - a), c = 0.5 * (a + b);
    double sum = 0.0;
    for (std::size_t i = 0; i < r.x.size(); ++i) sum += r.w[i] * g(c + h * r.x[i]);
    return h * sum;
}

// The directional albedo int f(wi, wo) cos(theta_o) d wo over the upper hemisphere, wi in the xz-plane: in
// (mu_o, phi_o), phi_o over [0, pi] doubled (every model is even in phi), each split where the models have kinks
// (mu_o = mu_i: the max and min of Oren-Nayar and Fujii; phi = pi/2: the sign of cos(phi)).
template <class F>
double directional_albedo(const Rule& r, double mu_i, F&& f) {
    const Vec3 wi(std::sqrt((1.0 - mu_i) * (1.0 + mu_i)), 0.0, mu_i);
    auto over_phi = [&](double mu_o) {
        const double s = std::sqrt((1.0 - mu_o) * (1.0 + mu_o));
        auto g = [&](double phi) { return f(wi, Vec3(s * std::cos(phi), s * std::sin(phi), mu_o)); };
        return integrate(r, 0.0, 0.5 * pi, g) + integrate(r, 0.5 * pi, pi, g);
    };
    auto g_mu = [&](double mu_o) { return mu_o * over_phi(mu_o); };
    return 2.0 * (integrate(r, 0.0, mu_i, g_mu) + integrate(r, mu_i, 1.0, g_mu));
}

double eval(const DiffuseModel& m, const Vec3& wi, const Vec3& wo, double alpha, double albedo) {
    return m.f(wi, wo, alpha, albedo, m.published.data());
}

// Directions over the hemisphere: zenith angles from the pole to z = 1e-6 (grazing), several azimuths.
std::vector<Vec3> directions() {
    std::vector<Vec3> out;
    const double grazing = std::acos(1e-6) * 180.0 / pi;
    for (double t : {0.0, 1e-4, 10.0, 30.0, 45.0, 60.0, 80.0, 89.0, 89.9, grazing})
        for (double p : {0.0, 37.0, 90.0, 135.0, 180.0, 251.0}) {
            out.push_back(direction_from_deg(t, p));
            if (t == 0.0) break;
        }
    return out;
}

}  // namespace

TEST_CASE("diffuse_models: the table is well formed and every name is found", "[diffuse]") {
    const auto& models = diffuse_models();
    REQUIRE(models.size() == 11);  // ten published baselines and smithlab-2026
    for (const DiffuseModel& m : models) {
        INFO(m.name);
        CHECK(m.parameters.size() == m.published.size());
        CHECK(m.f != nullptr);
        CHECK(!m.source.empty());
        CHECK(&find_diffuse_model(m.name) == &m);
    }
    CHECK(find_diffuse_model("hammon-2017").parameters ==
          std::vector<std::string_view>{"rough_a", "rough_b", "rough_c", "smooth", "multi"});
    CHECK(find_diffuse_model("hammon-2017").published == std::vector<double>{0.9, 0.4, 0.5, 1.05, 0.1159});
    CHECK(find_diffuse_model("oren-nayar").published == std::vector<double>{0.5});
}

TEST_CASE("diffuse_models: every range is one per constant and holds the starting constants", "[diffuse]") {
    for (const DiffuseModel& m : diffuse_models()) {
        INFO(m.name);
        if (m.ranges.empty()) continue;
        REQUIRE(m.ranges.size() == m.parameters.size());
        for (std::size_t i = 0; i < m.ranges.size(); ++i) {
            INFO(m.parameters[i]);
            CHECK(m.ranges[i].lo < m.ranges[i].hi);
            CHECK(m.published[i] >= m.ranges[i].lo);
            CHECK(m.published[i] <= m.ranges[i].hi);
            if (std::isfinite(m.ranges[i].lo) || std::isfinite(m.ranges[i].hi)) CHECK(!m.ranges[i].why.empty());
        }
    }
    // The fitted constants of the default GGX scene that leave their models' domains, and some that do not.
    const DiffuseModel &on = find_diffuse_model("oren-nayar"), &eon = find_diffuse_model("eon"),
                       &hl = find_diffuse_model("hammon-2017-linear"), &sl = find_diffuse_model("smithlab-2026");
    CHECK(outside_range(on, 0, 14.96) != nullptr);
    CHECK(outside_range(on, 0, 0.5) == nullptr);
    CHECK(outside_range(on, 0, -0.1) != nullptr);
    CHECK(outside_range(on, 0, NAN) != nullptr);
    CHECK(outside_range(eon, 0, 3.16) != nullptr);
    CHECK(outside_range(hl, 4, -0.005) != nullptr);  // multi
    CHECK(outside_range(hl, 1, -0.19) == nullptr);   // rough_b: free
    CHECK(outside_range(sl, 7, -1.0) != nullptr);    // multi_forward at its bound
    CHECK(outside_range(sl, 7, -0.13) == nullptr);
    CHECK(outside_range(find_diffuse_model("lambert"), 0, 1e9) == nullptr);  // no constants, no ranges
}

TEST_CASE("diffuse_models: smithlab-2026 at its starting constants is hammon-2017, so it is no baseline of its own",
          "[diffuse]") {
    const DiffuseModel &s = find_diffuse_model("smithlab-2026"), &h = find_diffuse_model("hammon-2017");
    CHECK_FALSE(s.own_baseline);
    for (const DiffuseModel& m : diffuse_models())
        if (m.name != "smithlab-2026") CHECK(m.own_baseline);
    for (double alpha : {0.01, 0.3, 1.0})
        for (double ti : {0.0, 40.0, 85.0})
            for (double phi : {0.0, 90.0, 180.0}) {
                const Vec3 wi = direction_from_deg(ti, 0.0), wo = direction_from_deg(60.0, phi);
                CHECK(s.f(wi, wo, alpha, 0.7, s.published.data()) == h.f(wi, wo, alpha, 0.7, h.published.data()));
            }
}

namespace {

// A model of one constant for the registry's refusals: Lambert scaled by k, with its GLSL.
constexpr std::string_view scaled_lambert_glsl = R"(float smithlab_scaled_lambert(float k, float albedo)
{
    return k * albedo * smithlab_inv_pi;
}
)";
DiffuseModel scaled_lambert() {
    return {
        .name = "scaled-lambert",
        .parameters = {"k"},
        .published = {1.0},
        .source = "a test model: k albedo/pi",
        .f = [](const Vec3&, const Vec3&, double, double albedo, const double* c) { return c[0] * lambert(albedo); },
        .glsl = Glsl{{scaled_lambert_glsl}, "smithlab_scaled_lambert({0}, albedo)"}};
}

// The message of the input_error registering m into a registry of the built-in models throws, empty where none.
std::string refusal(const DiffuseModel& m) {
    DiffuseRegistry r = builtin_diffuse_registry();
    try {
        r.add(m);
    } catch (const input_error& e) {
        return e.what();
    }
    CHECK(&r.at(m.name) == &r.list().back());
    return {};
}

}  // namespace

TEST_CASE("diffuse registry: a program's model is added after the built-in ones, and refused by name when wrong",
          "[diffuse]") {
    CHECK(refusal(scaled_lambert()).empty());
    using Catch::Matchers::Contains;
    auto with = [](auto&& change) {
        DiffuseModel m = scaled_lambert();
        change(m);
        return refusal(m);
    };
    CHECK_THAT(with([](DiffuseModel& m) { m.name = "lambert"; }), Contains("'lambert' is already registered"));
    CHECK_THAT(with([](DiffuseModel& m) { m.name = "Scaled"; }), Contains("cannot register diffuse model 'Scaled'"));
    CHECK_THAT(with([](DiffuseModel& m) { m.name = "scaled-fitted"; }), Contains("not ending in -fitted"));
    CHECK_THAT(with([](DiffuseModel& m) { m.name = "lambert-"; }), Contains("has the GLSL name of 'lambert'"));
    CHECK_THAT(with([](DiffuseModel& m) { m.source = {}; }), Contains("'scaled-lambert': no source"));
    CHECK_THAT(with([](DiffuseModel& m) { m.f = nullptr; }), Contains("'scaled-lambert': no f"));
    CHECK_THAT(with([](DiffuseModel& m) { m.published = {1.0, 2.0}; }), Contains("2 published values for 1 constants"));
    CHECK_THAT(with([](DiffuseModel& m) { m.ranges = {{}, {}}; }), Contains("2 ranges for 1 constants"));
    CHECK_THAT(with([](DiffuseModel& m) { m.parameters = {""}; }), Contains("constant 0 has no name"));
    CHECK_THAT(with([](DiffuseModel& m) {
                   m.parameters = {"k", "k"}, m.published = {1.0, 1.0};
               }),
               Contains("constant 'k' named twice"));
    // The GLSL call: of a function its functions or the common helpers define, with every constant and no other.
    auto call = [&](std::string_view c) {
        return with([&](DiffuseModel& m) { m.glsl = Glsl{{scaled_lambert_glsl}, c}; });
    };
    CHECK(call("smithlab_pow5({0}) * albedo").empty());
    CHECK_THAT(call("smithlab_lambert({0} * albedo)"),
               Contains("'scaled-lambert': its GLSL calls smithlab_lambert, which neither its functions nor"));
    CHECK_THAT(call("smithlab_scaled_lambert({1}, albedo)"), Contains("names {1}, not one of its constants"));
    CHECK_THAT(call("smithlab_scaled_lambert(1.0, albedo)"), Contains("leaves out constant {0} (k)"));
    CHECK_THAT(call("smithlab_scaled_lambert({k}, albedo)"), Contains("opens no {i}"));
    CHECK_THAT(call("2.0 * smithlab_scaled_lambert({0}, albedo)"), Contains("does not start with a function's name"));
}

TEST_CASE("diffuse_models: an unknown name is an input_error naming it and the known ones", "[diffuse]") {
    try {
        (void)find_diffuse_model("nope");
        FAIL("no exception");
    } catch (const input_error& e) {
        const std::string msg = e.what();
        CHECK(msg.find("nope") != std::string::npos);
        CHECK(msg.find("hammon-2017") != std::string::npos);
        CHECK(msg.find("lambert") != std::string::npos);
    }
}

TEST_CASE("diffuse_models: every model is symmetric in wi and wo", "[diffuse]") {
    const std::vector<Vec3> dirs = directions();
    for (const DiffuseModel& m : diffuse_models())
        for (double alpha : {1e-3, 0.1, 0.5, 0.9, 1.0})
            for (double albedo : {0.3, 1.0})
                for (const Vec3& wi : dirs)
                    for (const Vec3& wo : dirs) {
                        const double a = eval(m, wi, wo, alpha, albedo), b = eval(m, wo, wi, alpha, albedo);
                        if (!(std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)))) {
                            INFO(m.name << " alpha " << alpha << " wi " << wi.transpose() << " wo " << wo.transpose());
                            CHECK(a == Approx(b).epsilon(1e-12));
                        }
                    }
}

TEST_CASE("diffuse_models: finite and non-negative, grazing included", "[diffuse]") {
    const std::vector<Vec3> dirs = directions();
    for (const DiffuseModel& m : diffuse_models())
        for (double alpha : {1e-3, 0.5, 1.0})
            for (double albedo : {0.0, 0.5, 1.0})
                for (const Vec3& wi : dirs)
                    for (const Vec3& wo : dirs) {
                        const double v = eval(m, wi, wo, alpha, albedo);
                        if (!(std::isfinite(v) && v >= 0.0)) {
                            INFO(m.name << " alpha " << alpha << " albedo " << albedo << " wi " << wi.transpose()
                                        << " wo " << wo.transpose() << " f " << v);
                            CHECK(false);
                        }
                    }
}

TEST_CASE("diffuse_models: the rough models reduce to Lambert at zero roughness", "[diffuse]") {
    const std::vector<Vec3> dirs = directions();
    for (const Vec3& wi : dirs)
        for (const Vec3& wo : dirs) {
            // sigma = 0 exactly: every roughness term has a factor sigma^2 (Oren-Nayar) or sigma (Fujii), r (EON).
            CHECK(oren_nayar(wi, wo, 0.0, 0.7) == Approx(0.7 / pi).epsilon(1e-15));
            CHECK(oren_nayar_qualitative(wi, wo, 0.0, 0.7) == Approx(0.7 / pi).epsilon(1e-15));
            CHECK(fujii(wi, wo, 0.0, 0.7) == Approx(0.7 / pi).epsilon(1e-15));
            CHECK(eon(wi, wo, 0.0, 0.7) == Approx(0.7 / pi).epsilon(1e-15));
            // sigma -> 0 through the table. The roughness terms carry sin(alpha') tan(beta) (or s/t = cos(phi) times
            // it), up to 1/z: away from grazing (z >= 1e-3) it is at most 1e3. Oren-Nayar's terms are O(sigma^2):
            // alpha = 1e-9 leaves ~1e-15; Fujii's and EON's are O(sigma): alpha = 1e-12 leaves at most 1e-9.
            if (wi.z() < 1e-3 || wo.z() < 1e-3) continue;
            for (const char* name : {"oren-nayar", "oren-nayar-sqrt2", "oren-nayar-qualitative"})
                CHECK(eval(find_diffuse_model(name), wi, wo, 1e-9, 0.7) == Approx(0.7 / pi).epsilon(1e-12));
            for (const char* name : {"fujii", "eon"})
                CHECK(eval(find_diffuse_model(name), wi, wo, 1e-12, 0.7) == Approx(0.7 / pi).epsilon(2e-9));
        }
}

TEST_CASE("diffuse_models: Disney against values derived by hand", "[diffuse]") {
    // Normal incidence both ways: (1 - cos)^5 = 0, Lambert at any roughness.
    const Vec3 n(0, 0, 1);
    for (double alpha : {1e-3, 0.3, 1.0}) CHECK(disney_diffuse(n, n, std::sqrt(alpha), 0.6) == Approx(0.6 / pi));
    // Retro-reflection (wi = wo: theta_d = 0) at r = 1/4: FD90 = 0.5 + 2 r = 1, Lambert at every angle.
    for (const Vec3& w : directions())
        CHECK(eval(find_diffuse_model("disney"), w, w, 1.0 / 16.0, 0.6) == Approx(0.6 / pi).epsilon(1e-14));
    // wi = n, wo at 60 degrees, r = 1: cos^2(theta_d) = (1 + cos 60)/2 = 3/4, FD90 = 0.5 + 2 (3/4) = 2,
    // f = albedo/pi (1)(1 + (1/2)^5) = 33/32 albedo/pi.
    CHECK(disney_diffuse(n, direction_from_deg(60, 123), 1.0, 0.6) == Approx(33.0 / 32.0 * 0.6 / pi).epsilon(1e-14));
}

TEST_CASE("diffuse_models: Oren-Nayar against values derived by hand", "[diffuse]") {
    // theta_i = 30, theta_o = 60 degrees, phi = 90 degrees (cos(phi) = 0): the C2 term drops, C3's factor
    // (4 alpha' beta / pi^2)^2 = (4 (pi/3)(pi/6)/pi^2)^2 = (2/9)^2, tan((alpha' + beta)/2) = tan(pi/4) = 1, L2's
    // bracket 1.
    const Vec3 wi = direction_from_deg(30, 10), wo = direction_from_deg(60, 100);
    for (double sigma : {0.1, 0.35, 0.7}) {
        const double s2 = sigma * sigma, rho = 0.8;
        const double c1 = 1 - 0.5 * s2 / (s2 + 0.33), c3 = 0.125 * s2 / (s2 + 0.09) * (4.0 / 81.0);
        const double expect = rho / pi * (c1 + c3) + 0.17 * rho * rho / pi * s2 / (s2 + 0.13);
        CHECK(oren_nayar(wi, wo, sigma, rho) == Approx(expect).epsilon(1e-13));
        // The qualitative model there: A only.
        CHECK(oren_nayar_qualitative(wi, wo, sigma, rho) == Approx(rho / pi * c1).epsilon(1e-13));
    }
    // Retro-reflection in the plane (phi = 0, theta = 60 both): C2 with sin(alpha') tan(beta) = sin 60 tan 60 = 3/2,
    // L2's bracket 1 - (2/3)^2 = 5/9, no C3 (1 - |cos(phi)| = 0).
    const Vec3 w = direction_from_deg(60, 0);
    const double s2 = 0.25, rho = 0.5;
    const double c1 = 1 - 0.5 * s2 / (s2 + 0.33), b = 0.45 * s2 / (s2 + 0.09);
    CHECK(oren_nayar(w, w, 0.5, rho) ==
          Approx(rho / pi * (c1 + 1.5 * b) + 0.17 * rho * rho / pi * s2 / (s2 + 0.13) * 5.0 / 9.0).epsilon(1e-13));
    CHECK(oren_nayar_qualitative(w, w, 0.5, rho) == Approx(rho / pi * (c1 + 1.5 * b)).epsilon(1e-13));
    // Fujii at the same retro-reflection: s = sin^2 60 = 3/4, t = cos 60, s/t = 3/2.
    const double a_f = 1.0 / (1.0 + (0.5 - 2.0 / (3.0 * pi)) * 0.5);
    CHECK(fujii(w, w, 0.5, rho) == Approx(rho / pi * a_f * (1.0 + 0.5 * 1.5)).epsilon(1e-13));
}

TEST_CASE("diffuse_models: Chan 2018 against a value derived by hand", "[diffuse]") {
    // alpha = 1: a2 = 1, g = log2(1)/18 = 0, so Fd = F0 = V.H + (1 - V.H)^5 and
    // Fb = 24.5 V.H 2^(-max(-21.2, 8.9) sqrt(N.H)). Normal incidence both ways: V.H = N.H = 1, f = albedo/pi (1 + 24.5
    // 2^-8.9).
    const Vec3 n(0, 0, 1);
    CHECK(chan_2018(n, n, 1.0, 0.4) == Approx(0.4 / pi * (1.0 + 24.5 * std::exp2(-8.9))).epsilon(1e-14));
    CHECK(eval(find_diffuse_model("chan-2018"), n, n, 1.0, 0.4) == Approx(chan_2018(n, n, 1.0, 0.4)));
    // No retro-reflective weight: F0 alone.
    CHECK(chan_2018(n, n, 1.0, 0.4, 0.0) == Approx(0.4 / pi).epsilon(1e-14));
    // alpha -> 0: g = 1 (clamped), t = saturate(1.7) = 1, Fd = FdV FdL = 1 at normal incidence,
    // Fb = (34.5 - 59 + 24.5) ... = 0.
    CHECK(chan_2018(n, n, 1e-4, 0.4) == Approx(0.4 / pi).epsilon(1e-14));
}

TEST_CASE("diffuse_models: Hammon 2017 against the slide", "[diffuse]") {
    const Vec3 n(0, 0, 1);
    const DiffuseModel &h = find_diffuse_model("hammon-2017"), &hl = find_diffuse_model("hammon-2017-linear");
    // alpha = 0, normal incidence both ways: single = smooth/pi = 1.05 (1 - 0)(1 - 0)/pi, multi = 0.
    for (double albedo : {0.25, 1.0}) {
        CHECK(eval(h, n, n, 0.0, albedo) == Approx(1.05 / pi * albedo).epsilon(1e-15));
        CHECK(eval(hl, n, n, 0.0, albedo) == Approx(1.05 / pi * albedo).epsilon(1e-15));
    }
    // alpha = 1, normal incidence both ways: facing = 1, N.H = 1, rough = 1 (0.9 - 0.4)(0.5 + 1)/1 = 0.75,
    // single = 0.75/pi, multi = 0.1159: the two readings of the last line differ by albedo on multi.
    const double albedo = 0.5;
    CHECK(eval(h, n, n, 1.0, albedo) == Approx(albedo * (0.75 / pi + albedo * 0.1159)).epsilon(1e-14));
    CHECK(eval(hl, n, n, 1.0, albedo) == Approx(albedo * (0.75 / pi + 0.1159)).epsilon(1e-14));
    // The constants are what the fitter passes: doubling `smooth` doubles f at alpha = 0.
    const double c[] = {0.9, 0.4, 0.5, 2.1, 0.1159};
    CHECK(h.f(n, n, 0.0, 1.0, c) == Approx(2.1 / pi).epsilon(1e-15));
    // The normalisation k = 21/(20 pi): 2 pi int_0^1 k (1 - (1 - mu)^5) mu dmu = 1 (degree 6: exact with 4 points).
    const Rule r4 = gauss_legendre(4);
    const double hemi =
        2.0 * pi * integrate(r4, 0.0, 1.0, [](double mu) { return 1.05 / pi * (1.0 - std::pow(1.0 - mu, 5)) * mu; });
    CHECK(std::abs(hemi - 1.0) < 1e-12);
    // Hence the slide's f is the BRDF, not f cos: at alpha = 0 and wi = n the directional albedo of f is exactly 1.
    const Rule r = gauss_legendre(24);
    CHECK(directional_albedo(r, 1.0, [&](const Vec3& a, const Vec3& b) { return eval(h, a, b, 0.0, 1.0); }) ==
          Approx(1.0).epsilon(1e-12));
}

TEST_CASE("diffuse_models: EON passes the white furnace and is bounded by its albedo", "[diffuse]") {
    const Rule rule = gauss_legendre(32);
    double worst_furnace = 0.0, worst_fon = 0.0;
    for (double r : {0.0, 0.25, 0.5, 1.0})
        for (double theta : {0.0, 30.0, 60.0, 80.0, 89.0}) {
            const double mu = std::cos(theta * pi / 180.0);
            INFO("r " << r << " theta_i " << theta);
            // Albedo 1: the single- and multiple-scattering lobes together reflect everything (the paper's claim).
            const double e1 =
                directional_albedo(rule, mu, [&](const Vec3& a, const Vec3& b) { return eon(a, b, r, 1.0); });
            CHECK(std::abs(e1 - 1.0) < 1e-3);
            worst_furnace = std::max(worst_furnace, std::abs(e1 - 1.0));
            // The FON lobe alone against the paper's analytic E_F (the G(mu) the compensation lobe is built on).
            const double ef = directional_albedo(rule, mu, [&](const Vec3& a, const Vec3& b) {
                const double s = a.x() * b.x() + a.y() * b.y(), t = s > 0 ? std::max(a.z(), b.z()) : 1.0;
                return (1.0 + r * s / t) / (pi * (1.0 + (0.5 - 2.0 / (3.0 * pi)) * r));
            });
            CHECK(ef == Approx(eon_fon_albedo(mu, r)).epsilon(1e-6));
            worst_fon = std::max(worst_fon, std::abs(ef - eon_fon_albedo(mu, r)));
            // Albedo 0.5: below 0.5, and equal to the paper's E_EON.
            const double e5 =
                directional_albedo(rule, mu, [&](const Vec3& a, const Vec3& b) { return eon(a, b, r, 0.5); });
            CHECK(e5 <= 0.5 + 1e-9);
            CHECK(e5 == Approx(eon_albedo(mu, r, 0.5)).epsilon(1e-6));
        }
    // The average of E_F: 2 int E_F mu dmu against the closed form.
    for (double r : {0.25, 1.0}) {
        const double avg = 2.0 *
            (integrate(rule, 0.0, 0.5, [&](double mu) { return eon_fon_albedo(mu, r) * mu; }) +
             integrate(rule, 0.5, 1.0, [&](double mu) { return eon_fon_albedo(mu, r) * mu; }));
        CHECK(avg == Approx(eon_fon_average_albedo(r)).epsilon(1e-9));
    }
    std::printf("EON white furnace: max |E - 1| = %.3g; FON lobe vs the analytic E_F: max |diff| = %.3g\n",
                worst_furnace, worst_fon);
}

// A measurement, not an assertion of a number: the largest (and smallest) directional albedo at albedo 1, published
// constants, alpha in {0.1, ..., 1}, theta_i in 0..89 degrees. Values above 1 mean the model is not energy-bounded
// there; below 1, the energy it loses.
TEST_CASE("diffuse_models: maximum directional albedo at albedo 1 (measured, printed)", "[diffuse][sweep]") {
    const Rule rule = gauss_legendre(20);
    std::printf("%-24s %10s %6s %8s %13s %10s %6s %8s\n", "model", "max E", "alpha", "theta_i", "2x rule - 1x", "min E",
                "alpha", "theta_i");
    for (const DiffuseModel& m : diffuse_models()) {
        double best = 0.0, best_alpha = 0.0, best_theta = 0.0;
        double least = std::numeric_limits<double>::infinity(), least_alpha = 0.0, least_theta = 0.0;
        for (int ia = 1; ia <= 10; ++ia)
            for (int it = 0; it <= 89; ++it) {
                const double alpha = 0.1 * ia, mu = std::cos(it * pi / 180.0);
                const double e = directional_albedo(
                    rule, mu, [&](const Vec3& a, const Vec3& b) { return eval(m, a, b, alpha, 1.0); });
                REQUIRE(std::isfinite(e));
                if (e > best) best = e, best_alpha = alpha, best_theta = it;
                if (e < least) least = e, least_alpha = alpha, least_theta = it;
            }
        // The same maximum by a rule twice as fine: the difference is the quadrature's error there.
        const double finer =
            directional_albedo(gauss_legendre(40), std::cos(best_theta * pi / 180.0),
                               [&](const Vec3& a, const Vec3& b) { return eval(m, a, b, best_alpha, 1.0); });
        std::printf("%-24s %10.6f %6.1f %8.0f %13.2g %10.6f %6.1f %8.0f\n", std::string(m.name).c_str(), best,
                    best_alpha, best_theta, finer - best, least, least_alpha, least_theta);
    }
}

// ---- the models as GLSL (fit/glsl.hpp) ---------------------------------------------------------------------------

namespace {

// What write_shaders hands over: every model at its published constants on "ggx", and the ones with free constants
// at made-up fitted constants (published * 1.1 + 0.01, with standard errors) on "gtr(gamma=1.5)".
struct ShaderSet {
    std::vector<std::string> names;
    std::vector<std::vector<double>> constants, stderrs;
    std::vector<ShaderModel> models;
};
ShaderSet shader_set() {
    ShaderSet s;
    for (const DiffuseModel& m : diffuse_models()) {
        s.names.emplace_back(m.name);
        s.constants.push_back(m.published);
        s.stderrs.emplace_back();
        if (m.parameters.empty()) continue;
        s.names.push_back(std::string(m.name) + "-fitted");
        s.constants.emplace_back();
        for (double c : m.published) s.constants.back().push_back(1.1 * c + 0.01);
        s.stderrs.emplace_back(m.published.size(), 0.00123);
    }
    for (std::size_t i = 0; i < s.names.size(); ++i) {
        const bool fitted = !s.stderrs[i].empty();
        const std::string model = fitted ? s.names[i].substr(0, s.names[i].size() - 7) : s.names[i];
        s.models.push_back(
            {s.names[i], fitted ? "gtr(gamma=1.5)" : "ggx", &find_diffuse_model(model), s.constants[i], s.stderrs[i]});
    }
    return s;
}

std::filesystem::path scratch_dir(const char* what) {
    const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / (std::string("smithlab_") + what + "_" + std::to_string(now));
    std::filesystem::create_directories(dir);
    return dir;
}

// The shader section of a .brdf file.
std::string brdf_shader(const std::string& file) {
    const std::size_t begin = file.find("::begin shader\n"), end = file.find("::end shader");
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    return file.substr(begin + 15, end - begin - 15);
}

// A minimal vec3 and GLSL's built-ins the models use, in float, so that models.glsl compiles as C++ (GLSL's
// min(x, y) = y < x ? y : x, max(x, y) = x < y ? y : x, clamp = min(max(x, lo), hi)).
constexpr const char* glsl_as_cpp_shim = R"(#include <cmath>
#include <cstdio>
namespace glsl {
struct vec3 { float x, y, z; };
vec3 operator+(vec3 a, vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
vec3 operator-(vec3 a, vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
vec3 operator*(float s, vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
vec3 operator*(vec3 a, float s) { return s * a; }
float dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
float length(vec3 a) { return std::sqrt(dot(a, a)); }
float sqrt(float x) { return std::sqrt(x); }
float acos(float x) { return std::acos(x); }
float atan(float y, float x) { return std::atan2(y, x); }
float log2(float x) { return std::log2(x); }
float exp2(float x) { return std::exp2(x); }
float abs(float x) { return std::fabs(x); }
float pow(float x, float y) { return std::pow(x, y); }
float min(float x, float y) { return y < x ? y : x; }
float max(float x, float y) { return x < y ? y : x; }
float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
)";

}  // namespace

TEST_CASE("glsl: names, literals and refusals", "[diffuse][glsl]") {
    CHECK(glsl_identifier("gtr(gamma=1.5)") == "gtr_gamma_1p5");
    CHECK(glsl_identifier("hammon-2017-fitted") == "hammon_2017_fitted");
    CHECK(glsl_identifier("--GGX  ") == "ggx");
    CHECK_THROWS_AS(glsl_identifier("()"), input_error);
    CHECK(glsl_float(1.0) == "1.0");
    CHECK(glsl_float(0.1159) == "0.1159");
    CHECK(glsl_float(1.0 / 3.0) == "0.333333333");
    CHECK(glsl_float(-2.5e-7) == "(-2.5e-07)");
    CHECK(glsl_float(1e20) == "1e+20");
    CHECK_THROWS_AS(glsl_float(std::numeric_limits<double>::quiet_NaN()), input_error);
    const DiffuseModel& hammon = find_diffuse_model("hammon-2017");
    const std::vector<double> k{0.9, 0.4, 0.5, 1.05, 0.1159}, e{0.01, 0.02, 0.03, 0.04, 0.005};
    const ShaderModel m{"hammon-2017-fitted", "gtr(gamma=1.5)", &hammon, k, e};
    CHECK(glsl_function_name(m) == "smithlab_hammon_2017_fitted_gtr_gamma_1p5");
    const std::string f = glsl_function(m);
    CHECK(f.find("float smithlab_hammon_2017_fitted_gtr_gamma_1p5(vec3 L, vec3 V, vec3 N, float alpha, "
                 "float albedo)") != std::string::npos);
    CHECK(f.find("smithlab_hammon_2017(L, V, N, alpha, albedo, 0.9, 0.4, 0.5, 1.05, 0.1159)") != std::string::npos);
    CHECK(f.find("rough_a = 0.9 +- 0.01") != std::string::npos);
    CHECK(f.find(std::string(hammon.source)) != std::string::npos);
    const std::vector<double> four{0.9, 0.4, 0.5, 1.05};
    CHECK_THROWS_AS(glsl_function({"hammon-2017", "ggx", &hammon, four, {}}), input_error);
    const DiffuseModel unknown{.name = "unknown-model", .source = "nowhere", .glsl = no_glsl};
    try {
        (void)glsl_function({"unknown-model", "ggx", &unknown, {}, {}});
        FAIL("no exception");
    } catch (const input_error& ex) {
        CHECK(std::string(ex.what()).find("unknown-model") != std::string::npos);
    }
    const std::string brdf = brdf_explorer_file(m, glsl_helpers({&m, 1}));
    CHECK(brdf.rfind("analytic\n", 0) == 0);
    CHECK(brdf.find("::begin parameters\nfloat albedo 0 1 0.75\nfloat alpha 0.001 1 0.25\n::end parameters\n") !=
          std::string::npos);
    CHECK(brdf.find("::begin shader\n") < brdf.find("vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )"));
    CHECK(brdf.find("vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )") < brdf.find("::end shader"));
}

namespace {

// The models the fit cannot export as GLSL, by name: those that have none (no_glsl), and those whose transcription
// glsl_transcription_problem refuses.
std::vector<std::string> models_without_glsl(const std::vector<DiffuseModel>& models) {
    std::vector<std::string> out;
    for (const DiffuseModel& m : models)
        if (!m.glsl.get() || !glsl_transcription_problem(m).empty()) out.emplace_back(m.name);
    return out;
}

// Whether a DiffuseModel can be written without naming its GLSL, or with no_glsl.
template <class M>
concept builds_without_glsl = requires {
    M{.name = "m", .source = "s", .f = nullptr};
};
template <class M>
concept builds_with_no_glsl = requires {
    M{.name = "m", .source = "s", .f = nullptr, .glsl = no_glsl};
};

}  // namespace

// What the fit exports: every registered model has GLSL; the library defines one function per model and NDF, each
// returning a call of a function defined above it, and every function once (glslangValidator compiles it below).
TEST_CASE("glsl: every registered model has its GLSL, and the library a function per model calling what it defines",
          "[diffuse][glsl]") {
    CHECK(models_without_glsl(diffuse_models()).empty());
    const ShaderSet s = shader_set();
    const std::string library = glsl_library(s.models);
    for (const ShaderModel& m : s.models) {
        INFO(m.name << " on " << m.ndf);
        const std::string head =
            "\nfloat " + glsl_function_name(m) + "(vec3 L, vec3 V, vec3 N, float alpha, float albedo)\n{\n    return ";
        const std::size_t at = library.find(head);
        REQUIRE(at != std::string::npos);
        CHECK(library.find(head, at + 1) == std::string::npos);
        const std::size_t call = at + head.size();
        const std::string callee = library.substr(call, library.find('(', call) - call);
        CHECK_THAT(callee, Catch::Matchers::StartsWith("smithlab_"));
        CHECK(library.find("\nfloat " + callee + "(") < at);
    }
    // Every function once: one per exported model, the common helpers', and each distinct function the models name.
    const std::regex definition("\nfloat (\\w+)\\(");
    auto definitions = [&](const std::string& text) {
        std::vector<std::string> out;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), definition); it != std::sregex_iterator(); ++it)
            out.push_back((*it)[1]);
        return out;
    };
    std::string common_text(1, '\n');
    common_text += common::glsl_functions;
    const std::vector<std::string> common_names = definitions(common_text);
    CHECK(common_names.size() == 5);  // pow5, tangential_dot, s_over_t, eon_g, eon_rho_ms
    std::vector<std::string_view> named;
    for (const DiffuseModel& m : diffuse_models())
        if (const Glsl* glsl = m.glsl.get())
            for (std::string_view f : glsl->functions)
                if (std::find(named.begin(), named.end(), f) == named.end()) named.push_back(f);
    std::vector<std::string> defined = definitions(library);
    CHECK(defined.size() == s.models.size() + common_names.size() + named.size());
    std::sort(defined.begin(), defined.end());
    CHECK(std::adjacent_find(defined.begin(), defined.end()) == defined.end());
}

// A model without GLSL does not compile unless it says so (no_glsl); one that says so is listed by the check above,
// named in the library as having none, and refused by glsl_function.
TEST_CASE("glsl: a model without GLSL says so, and the check above finds it", "[diffuse][glsl]") {
    static_assert(!builds_without_glsl<DiffuseModel>);
    static_assert(builds_with_no_glsl<DiffuseModel>);
    DiffuseRegistry r = builtin_diffuse_registry();
    r.add({.name = "untranscribed",
           .source = "a test model: Lambert without GLSL",
           .f = [](const Vec3&, const Vec3&, double, double albedo, const double*) { return lambert(albedo); },
           .glsl = no_glsl});
    CHECK(models_without_glsl(r.list()) == std::vector<std::string>{"untranscribed"});
    CHECK(glsl_transcription_problem(r.at("untranscribed")).empty());  // nothing to refuse: there is none
    const ShaderModel models[] = {{"lambert", "ggx", &r.at("lambert"), {}, {}},
                                  {"untranscribed", "ggx", &r.at("untranscribed"), {}, {}}};
    const std::string library = glsl_library(models);
    CHECK_THAT(library,
               Catch::Matchers::Contains("\n// untranscribed on ggx: no GLSL transcription (the model has none)\n"));
    CHECK_THAT(library, !Catch::Matchers::Contains("smithlab_untranscribed_ggx"));
    CHECK_THAT(library, Catch::Matchers::Contains("float smithlab_lambert_ggx("));
    CHECK_THROWS_WITH(glsl_function(models[1]), Catch::Matchers::Contains("'untranscribed' has no GLSL transcription"));
    // The helpers are the common ones and those the exported models name: Lambert's here, none of the others'.
    CHECK_THAT(library, Catch::Matchers::Contains("float smithlab_lambert(float albedo)"));
    CHECK_THAT(library, !Catch::Matchers::Contains("float smithlab_chan_2018("));
    CHECK_THAT(library, Catch::Matchers::Contains("float smithlab_eon_rho_ms("));
}

// Every model's GLSL through the reference compiler: models.glsl in a fragment shader (#version 330 core), and each
// .brdf's shader section as BRDF Explorer compiles it (#version 410, its template's uniforms, the parameters as
// uniforms).
TEST_CASE("glsl: every model compiles with glslangValidator", "[diffuse][glsl]") {
    const std::string validator = "/usr/bin/glslangValidator";
    if (!std::filesystem::exists(validator)) {
        WARN("no " << validator << " (Debian: glslang-tools): the GLSL is not compiled");
        return;
    }
    const ShaderSet s = shader_set();
    const std::filesystem::path dir = scratch_dir("glsl");
    std::string frag = "#version 330 core\n" + glsl_library(s.models) +
        "\nuniform vec3 L;\nuniform vec3 V;\nuniform vec3 N;\n"
        "uniform float alpha;\nuniform float albedo;\n"
        "out vec4 color;\n\nvoid main()\n{\n    float f = 0.0;\n";
    for (const ShaderModel& m : s.models) frag += "    f += " + glsl_function_name(m) + "(L, V, N, alpha, albedo);\n";
    frag += "    color = vec4(f);\n}\n";
    std::ofstream(dir / "models.frag") << frag;
    const std::string quiet = " > " + (dir / "log.txt").string() + " 2>&1";
    CHECK(std::system((validator + " " + (dir / "models.frag").string() + quiet).c_str()) == 0);
    for (std::size_t i = 0; i < s.models.size(); ++i) {
        INFO(s.models[i].name << " on " << s.models[i].ndf);
        const std::string path = (dir / ("brdf" + std::to_string(i) + ".frag")).string();
        std::ofstream(path) << "#version 410\n"
                               "uniform vec3 incidentVector;\nuniform float incidentTheta;\n"
                               "uniform float incidentPhi;\n"
                               "uniform float brightness;\nuniform float gamma;\nuniform float exposure;\n"
                               "uniform float useNDotL;\nin vec4 worldSpaceVert;\nout vec4 fragColor;\n"
                               "uniform float albedo;\nuniform float alpha;\n"
                            << brdf_shader(brdf_explorer_file(s.models[i], glsl_helpers(s.models)))
                            << "void main(void)\n{\n    vec3 n = normalize(worldSpaceVert.xyz);\n"
                               "    vec3 t = normalize(cross(vec3(0, 1, 0), n)), b = normalize(cross(n, t));\n"
                               "    fragColor = vec4(BRDF(incidentVector, vec3(0, 0, 1), n, t, b), 1.0);\n}\n";
        CHECK(std::system((validator + " " + path + quiet).c_str()) == 0);
    }
    std::filesystem::remove_all(dir);
}

// The GLSL against the C++ model: models.glsl compiled as C++ (the shim above) and run on the directions of the other
// cases x alpha x albedo, each input rounded to float and the C++ model given the same rounded values. Twice:
//  - read with `float` as double and the helpers' 9-digit literals (pi, 1/pi, EON's c1 and c2, sqrt(2)) at 17
//    digits: the transcription itself, on every direction (the pole, 1e-4 degrees from it, grazing at z = 1e-6),
//    within 1e-12 (measured: 0 at published constants; 6e-16 where the fitted constants lost their 17th digit);
//  - as GLSL has it, in float, to zenith angles of 89 degrees: 1e-5 to 80 degrees, 5e-5 beyond. Nearer grazing
//    float itself is the limit, not the transcription: Oren-Nayar's tan(beta) (1e6 at z = 1e-6) multiplies
//    sin(alpha') - (2 beta/pi)^3, which cancels to 2e-6 (0.4 relative in float, 0.03 in double with pi at 9 digits);
//    at 89 degrees, opposite, Fujii's and EON's 1 + r s/t cancels to 3e-4.
// Differences relative to f or, where f nearly vanishes (Oren-Nayar's and Fujii's max(0, f)), to 1e-3 albedo/pi.
TEST_CASE("glsl: models.glsl agrees with the C++ models", "[diffuse][glsl]") {
    if (std::system("g++ --version > /dev/null 2>&1") != 0) {
        WARN("no g++ on PATH: the GLSL is not run");
        return;
    }
    const ShaderSet s = shader_set();
    const std::filesystem::path dir = scratch_dir("glsl_cpp");
    std::string program = std::string(glsl_as_cpp_shim) + glsl_library(s.models) + "}  // namespace glsl\n\n" +
        "using Fn = float (*)(glsl::vec3, glsl::vec3, glsl::vec3, float, float);\n" + "const Fn fns[] = {\n";
    for (const ShaderModel& m : s.models) program += "    glsl::" + glsl_function_name(m) + ",\n";
    program +=
        "};\n\nint main(int, char** argv)\n{\n"
        "    std::FILE* in = std::fopen(argv[1], \"r\");\n    std::FILE* out = std::fopen(argv[2], \"w\");\n"
        "    double p[8];\n"
        "    while (std::fscanf(in, \"%lf %lf %lf %lf %lf %lf %lf %lf\", p, p + 1, p + 2, p + 3, p + 4, p + 5, "
        "p + 6, p + 7) == 8) {\n"
        "        glsl::vec3 l{float(p[0]), float(p[1]), float(p[2])};\n"
        "        glsl::vec3 v{float(p[3]), float(p[4]), float(p[5])}, n{0, 0, 1};\n"
        "        for (Fn f : fns) std::fprintf(out, \"%.17g \", double(f(l, v, n, float(p[6]), float(p[7]))));\n"
        "        std::fprintf(out, \"\\n\");\n    }\n    return 0;\n}\n";

    struct Point {
        Vec3 wi, wo;
        double alpha, albedo;
    };
    auto to_float = [](const Vec3& w) {
        return Vec3(static_cast<float>(w.x()), static_cast<float>(w.y()), static_cast<float>(w.z()));
    };
    const std::vector<Vec3> dirs = directions();
    const double z_89 = std::cos(89.0 * pi / 180.0) * (1.0 - 1e-9), z_80 = std::cos(80.0 * pi / 180.0) * (1.0 - 1e-9);
    // Runs `text` on the grid (directions with z >= z_min) and compares: the largest relative difference per model,
    // checked against tolerance(point).
    auto compare = [&](const std::string& name, const std::string& text, double z_min, auto&& tolerance) {
        std::vector<Point> grid;
        for (double alpha : {1e-3, 0.25, 0.5, 1.0})
            for (double albedo : {0.3, 1.0})
                for (const Vec3& wi : dirs)
                    for (const Vec3& wo : dirs)
                        if (wi.z() >= z_min && wo.z() >= z_min)
                            grid.push_back(
                                {to_float(wi), to_float(wo), static_cast<float>(alpha), static_cast<float>(albedo)});
        const std::string src = (dir / (name + ".cpp")).string(), exe = (dir / name).string(),
                          points = (dir / (name + ".in")).string(), values = (dir / (name + ".out")).string();
        std::ofstream(src) << text;
        REQUIRE(std::system(("g++ -std=c++17 -O1 -o " + exe + " " + src).c_str()) == 0);
        {
            std::ofstream out(points);
            char line[400];
            for (const Point& p : grid) {
                std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.wi.x(),
                              p.wi.y(), p.wi.z(), p.wo.x(), p.wo.y(), p.wo.z(), p.alpha, p.albedo);
                out << line;
            }
        }
        REQUIRE(std::system((exe + " " + points + " " + values).c_str()) == 0);
        std::ifstream in(values);
        std::vector<double> worst(s.models.size(), 0.0), worst_ratio(s.models.size(), 0.0);
        std::vector<std::size_t> worst_at(s.models.size(), 0);
        for (std::size_t i = 0; i < grid.size(); ++i)
            for (std::size_t j = 0; j < s.models.size(); ++j) {
                double glsl = std::numeric_limits<double>::quiet_NaN();
                REQUIRE(in >> glsl);
                const Point& p = grid[i];
                const ShaderModel& m = s.models[j];
                const double cpp = m.model->f(p.wi, p.wo, p.alpha, p.albedo, m.constants.data());
                const double d = std::abs(glsl - cpp) / std::max(std::abs(cpp), 1e-3 * p.albedo / pi);
                if (!(d <= worst[j])) worst[j] = d, worst_at[j] = i;
                worst_ratio[j] = std::max(worst_ratio[j], d / tolerance(p));
            }
        for (std::size_t j = 0; j < s.models.size(); ++j) {
            const Point& p = grid[worst_at[j]];
            std::printf("glsl as %-6s vs C++ (%zu points): %-40s max rel diff %.2e (z_i %.3g, z_o %.3g, alpha %g)\n",
                        name.c_str(), grid.size(), glsl_function_name(s.models[j]).c_str(), worst[j], p.wi.z(),
                        p.wo.z(), p.alpha);
            INFO(s.models[j].name << " on " << s.models[j].ndf << " read as " << name);
            CHECK(worst_ratio[j] <= 1.0);
        }
    };
    std::string as_double = std::regex_replace(program, std::regex("\\bfloat\\b"), "double");
    auto exact = [&](const std::string& literal, double value) {
        char digits[40];
        std::snprintf(digits, sizeof digits, "%.17g", value);
        const std::size_t at = as_double.find(literal);
        REQUIRE(at != std::string::npos);
        as_double.replace(at, literal.size(), digits);
    };
    exact(glsl_float(pi), pi);  // each one once, in the constant's definition
    exact(glsl_float(1.0 / pi), 1.0 / pi);
    exact(glsl_float(0.5 - 2.0 / (3.0 * pi)), 0.5 - 2.0 / (3.0 * pi));
    exact(glsl_float(2.0 / 3.0 - 28.0 / (15.0 * pi)), 2.0 / 3.0 - 28.0 / (15.0 * pi));
    as_double = std::regex_replace(as_double, std::regex("1\\.41421356\\b"), "1.4142135623730951");
    compare("double", as_double, 0.0, [](const Point&) { return 1e-12; });
    compare("float", program, z_89, [&](const Point& p) { return p.wi.z() >= z_80 && p.wo.z() >= z_80 ? 1e-5 : 5e-5; });
    std::filesystem::remove_all(dir);
}
