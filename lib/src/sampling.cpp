#include "smithlab/sampling.hpp"

#include <cmath>
#include <string>

#include "smithlab/errors.hpp"
#include "smithlab/ndfs.hpp"

namespace smithlab {

namespace {

[[noreturn]] void give_up(const std::string& sampler) {
    throw input_error(sampler + ": no sample accepted in 1e7 tries (a law that cannot be drawn in double)");
}

void require_unit(const Vec3& w, const std::string& what) {
    if (!(std::abs(w.squaredNorm() - 1.0) < 1e-9))
        throw input_error(what + " must be a unit vector (|w|^2 = " + std::to_string(w.squaredNorm()) + ")");
}

// A normal from draw() with a positive, finite pdf: one of underflowing density is drawn again; a draw that
// returns no_normal() gives up.
template <class Draw, class Pdf>
NormalSample with_pdf(const Draw& draw, const Pdf& pdf, const std::string& who) {
    for (long tries = 0; tries < max_tries; ++tries) {
        const Vec3 m = draw();
        if (std::isnan(m.x())) give_up(who);
        const double p = pdf(m);
        if (p > 0.0 && p < INFINITY) return {m, p};
    }
    give_up(who);
}

// A visible normal with a positive, finite pdf. Where none is visible (A(wi) = 0: straight down, or a projected area
// that underflows in double) input_error at the first draw, which is then refused or of pdf 0.
template <Ndf N>
NormalSample visible_sample(const VisibleNormals<N>& normals, const Vec3& wi, Rng& g, const std::string& who) {
    require_unit(wi, who + ": wi");
    for (long tries = 0; tries < max_tries; ++tries) {
        const Vec3 m = normals.sample(wi, g);
        const double p = std::isnan(m.x()) ? 0.0 : normals.pdf(wi, m);
        if (p > 0.0 && p < INFINITY) return {m, p};
        if (!(normals.projected_area(wi) > 0.0))
            throw input_error(who +
                              ": no microfacet normal is visible from wi (straight down, or a projected area that "
                              "underflows in double)");
        if (std::isnan(m.x())) give_up(who);
    }
    give_up(who);
}

// ln N(w) and d ln N / dw for N(w) = ierfc(w) + (w - b) erfc(w), w >= b (detail/visible_normals_closed.hpp). Below w =
// 6 directly (ierfc(w) = e^{-w^2}/sqrt(pi) - w erfc(w) cancels at most a factor 2 w^2 < 72 for w > 0, nothing below);
// above, scaled by sqrt(pi) e^{w^2}, the asymptotic series of both, positive: E = sqrt(pi) e^{w^2} N. dN/dw =
// -(w - b) (2 / sqrt(pi)) e^{-w^2}.
struct LogN {
    double value, slope;
};
LogN beckmann_log_N(double w, double b) {
    constexpr double sqrt_pi = 1.7724538509055160273;
    if (w < 6.0) {
        const double gauss = std::exp(-w * w) / sqrt_pi, erfc_w = std::erfc(w);
        const double N = (gauss - w * erfc_w) + (w - b) * erfc_w;
        return {std::log(N), -2.0 * (w - b) * gauss / N};
    }
    const double E = detail::ierfc_scaled_asymptotic(w) + (w - b) * detail::erfc_scaled_asymptotic(w);
    return {-w * w + std::log(E / sqrt_pi), -2.0 * (w - b) / E};
}

}  // namespace

// ---- D cos ----------------------------------------------------------------------------------------------

NormalSample DcosSampler::sample(Rng& g) const {
    return with_pdf([&] { return law_.sample(g); }, [&](const Vec3& m) { return law_.pdf(m); }, "D cos sampler");
}

// ---- visible normals ------------------------------------------------------------------------------------

NormalSample VisibleNormalSampler::sample(const Vec3& wi, Rng& g) const {
    return visible_sample(*normals_, wi, g, "visible-normal sampler");
}

NormalSample sample_ggx_visible(double alpha, const Vec3& wi, Rng& g) {
    return visible_sample(VisibleNormals<Ggx>(Ggx{alpha}), wi, g, "ggx visible-normal sampler");
}

double pdf_ggx_visible(double alpha, const Vec3& wi, const Vec3& m) {
    return VisibleNormals<Ggx>(Ggx{alpha}).pdf(wi, m);
}

// Newton's method on ln N, concave (N is the survival function of a log-concave density), so that from either side
// of the root its steps converge, monotonically once right of it; kept inside the bracket [lo, hi] all the same. Once
// the residual in ln N is below 1e-9, one more step leaves ~1e-18 (quadratic convergence): it is taken and returned.
double detail::beckmann_visible_slope(double mu, double u) {
    const double b = -mu, target = std::log(u) + beckmann_log_N(b, b).value;
    // Starts: for b >= 1 the law of t = w - b is ~ Gamma(2, 1 / (2b)), survival (1 + z) e^{-z} at z = 2bt, solved by
    // two fixed-point steps; else about the mode of (w - b) e^{-w^2}, right of it.
    double w;
    if (b >= 1.0) {
        double z = -std::log(u);
        z = -std::log(u) + std::log1p(z);
        z = -std::log(u) + std::log1p(z);
        w = b + std::max(z, 1e-3) / (2.0 * b);
    } else {
        w = 0.5 * (b + std::sqrt(b * b + 2.0)) + 0.5 * std::sqrt(-std::log(u));
    }
    double lo = b, hi = INFINITY;
    for (int i = 0; i < 100; ++i) {
        const LogN f = beckmann_log_N(w, b);
        const double d = f.value - target;
        if (d > 0.0) lo = w;
        else hi = w;
        double next = f.slope < 0.0 ? w - d / f.slope : NAN;
        if (std::abs(d) <= 1e-9 && next > b) return -next;
        if (!(next > lo && next < hi)) next = hi < INFINITY ? 0.5 * (lo + hi) : lo + 2.0 * (lo - b) + 1.0;
        w = next;
    }
    return -w;
}

// ---- Hammon ---------------------------------------------------------------------------------------------

Vec3 HammonSampler::sample_normal(const Vec3& wi, Rng& g) const {
    require_unit(wi, "hammon sampler: wi");
    if (wi.x() == 0.0 && wi.y() == 0.0 && wi.z() < 0.0)
        throw input_error("hammon sampler: no microfacet faces a ray travelling straight up");
    const Vec3 m = sample_hammon_normal(law_, wi, g);
    if (std::isnan(m.x())) give_up("hammon sampler");
    return m;
}

double HammonSampler::facing_fraction(const Vec3& wi) const {
    require_unit(wi, "hammon sampler: wi");
    return hammon_facing_fraction(law_, wi);
}

}  // namespace smithlab
