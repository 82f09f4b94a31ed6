// The diffuse models of issue 12 (fit/diffuse_models.hpp), each against something independent of its code: the
// symmetry every BRDF owes, limits derived by hand (Lambert at zero roughness), values derived by hand from the
// papers' formulas at convenient angles, and hemisphere integrals by a 2D Gauss-Legendre rule written here.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "smithlab/errors.hpp"
#include "smithlab/fit/diffuse_models.hpp"
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
    REQUIRE(models.size() == 10);
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
        const double avg = 2.0 * (integrate(rule, 0.0, 0.5, [&](double mu) { return eon_fon_albedo(mu, r) * mu; }) +
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
