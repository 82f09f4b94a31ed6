#include "smithlab/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "smithlab/errors.hpp"
#include "smithlab/ndfs.hpp"

namespace smithlab {

namespace {
constexpr double pi = std::numbers::pi;

// Rejection loops give up (input_error) after this many tries instead of hanging: every loop here accepts with
// probability >= 1/pi per try for any accepted NDF and direction, so reaching it means a law that cannot be drawn.
constexpr long max_tries = 10'000'000;
[[noreturn]] void give_up(const char* sampler) {
    throw input_error(std::string(sampler) + ": no sample accepted in 1e7 tries (a law that cannot be drawn in double)");
}

// 1 + Lambda(mu) for the visible-normal pdfs. Past mu = 1e12 (within 1e-10 degrees of the normal), beyond the range
// of the quadrature routes, Lambda is carried on as C/mu^2 from 1e12: the asymptote of every slope law with a tail
// P22 ~ r^-4 or lighter (every built-in NDF), where Lambda(1e12) r0^-2 ~ 1e-24 is already below double's resolution
// of 1 + Lambda unless the slope scale r0 is huge (GGX alpha = 1e40), and then the asymptote is exact.
double one_plus_Lambda(const LambdaTable& t, double mu) {
    constexpr double far = 1e12;
    if (mu <= far) return 1.0 + t.Lambda(mu);
    const double r = far / mu;
    return 1.0 + t.Lambda(far) * r * r;
}

void require_unit(const Vec3& w, const char* what) {
    if (!(std::abs(w.squaredNorm() - 1.0) < 1e-9))
        throw input_error(std::string(what) + " must be a unit vector (|w|^2 = " + std::to_string(w.squaredNorm()) + ")");
}
}  // namespace


// ---- D cos ----------------------------------------------------------------------------------------------

NormalSample DcosSampler::sample(Rng& g) const {
    for (long tries = 0; tries < max_tries; ++tries) {
        const double s = isf_(1.0 - uniform01(g));  // v in (0, 1]: s finite
        const Vec3 m = normal_from_slope(s, 2.0 * pi * uniform01(g));
        const double p = pdf(m);
        if (p > 0.0 && p < INFINITY) return {m, p};  // a normal of underflowing density is drawn again
    }
    give_up("D cos sampler");
}

double DcosSampler::pdf(const Vec3& m) const {
    if (!(m.z() > 0.0)) return 0.0;
    const double s = tan2_theta(m);
    return P22_(s) * (1.0 + s) * std::sqrt(1.0 + s);
}

// ---- visible normals, any NDF ---------------------------------------------------------------------------

NormalSample VisibleNormalSampler::sample(const Vec3& wi, Rng& g) const {
    require_unit(wi, "visible-normal sampler: wi");
    if (!(wi.z() > 0.0)) throw input_error("visible-normal sampler: wi must be above the surface (wi.z > 0)");
    const double sin_i = std::hypot(wi.x(), wi.y());
    if (sin_i == 0.0) return dcos_.sample(g);  // normal incidence: D_wi = D cos
    const double mu = wi.z() / sin_i, cos_phi = wi.x() / sin_i, sin_phi = wi.y() / sin_i;
    const double p_dcos = mu / (mu + 2.0 * pi * r_law_->total());
    for (long tries = 0; tries < max_tries; ++tries) {
        const double v = 1.0 - uniform01(g);
        const double s = uniform01(g) < p_dcos ? dcos_.isf(v) : r_law_->isf(v);
        const double r = std::sqrt(s), phi = 2.0 * pi * uniform01(g);
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        if (uniform01(g) * (mu + r) >= mu - x) continue;  // accept with (mu - x)^+ / (mu + r)
        // The normal of slope (x, y) is (-x, -y, 1)/|.|, then turned back to wi's azimuth.
        const double n = 1.0 / std::sqrt(1.0 + s);
        const Vec3 m{(-x * cos_phi + y * sin_phi) * n, (-x * sin_phi - y * cos_phi) * n, n};
        const double p = pdf(wi, m);
        if (p > 0.0 && p < INFINITY) return {m, p};
    }
    give_up("visible-normal sampler");
}

double VisibleNormalSampler::pdf(const Vec3& wi, const Vec3& m) const {
    const double wm = wi.dot(m);
    if (!(m.z() > 0.0 && wm > 0.0 && wi.z() > 0.0)) return 0.0;
    const double s = tan2_theta(m);
    return wm * D_from_P22(dcos_.P22(s), s) / (wi.z() * one_plus_Lambda(*Lambda_, cot_theta(wi)));
}

double VisibleNormalSampler::table_error() const {
    return std::max({dcos_.table_error(), r_law_->error_estimate(), Lambda_->error_estimate()});
}

// ---- visible normals, GGX -------------------------------------------------------------------------------

NormalSample sample_ggx_visible(double alpha, const Vec3& wi, Rng& g) {
    require_unit(wi, "ggx visible-normal sampler: wi");
    if (!(wi.z() > 0.0)) throw input_error("ggx visible-normal sampler: wi must be above the surface (wi.z > 0)");
    const Vec3 wi_std = Vec3(alpha * wi.x(), alpha * wi.y(), wi.z()).normalized();
    for (long tries = 0; tries < max_tries; ++tries) {
        const double phi = 2.0 * pi * uniform01(g);
        const double z = (1.0 - uniform01(g)) * (1.0 + wi_std.z()) - wi_std.z();
        const double sin_t = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
        const Vec3 h = Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), z) + wi_std;
        if (!(h.z() > 0.0)) continue;
        const Vec3 m = Vec3(alpha * h.x(), alpha * h.y(), h.z()).normalized();
        const double p = pdf_ggx_visible(alpha, wi, m);
        if (p > 0.0 && p < INFINITY) return {m, p};
    }
    give_up("ggx visible-normal sampler");
}

double pdf_ggx_visible(double alpha, const Vec3& wi, const Vec3& m) {
    const double wm = wi.dot(m);
    if (!(m.z() > 0.0 && wm > 0.0 && wi.z() > 0.0)) return 0.0;
    const Ggx ggx{alpha};
    const double s = tan2_theta(m);
    return wm * D_from_P22(ggx.slope_density(s), s) / (wi.z() * (1.0 + ggx.Lambda(cot_theta(wi))));  // Lambda(inf) = 0
}

// ---- Hammon ---------------------------------------------------------------------------------------------

Vec3 HammonSampler::sample_normal(const Vec3& wi, Rng& g) const {
    require_unit(wi, "hammon sampler: wi");
    const Vec3 T = -wi;
    const double Txy2 = T.x() * T.x() + T.y() * T.y();
    if (Txy2 == 0.0 && T.z() > 0.0) throw input_error("hammon sampler: no microfacet faces a ray travelling straight up");
    // Hammon's shrink: only u1 >= F(tan^2 theta_c) can face an upward ray, i.e. v = 1 - u1 <= S(tan^2 theta_c).
    const double S_c = T.z() > 0.0 ? dcos_.sf(T.z() * T.z() / Txy2) : 1.0;
    for (long tries = 0; tries < max_tries; ++tries) {
        const double s = dcos_.isf(S_c * (1.0 - uniform01(g)));
        const Vec3 m = normal_from_slope(s, 2.0 * pi * uniform01(g));
        if (T.dot(m) < 0.0) return m;
        if (T.z() > 0.0) {
            const Vec3 turned(-m.x(), -m.y(), m.z());
            if (T.dot(turned) < 0.0) return turned;
        }
    }
    give_up("hammon sampler");
}

double HammonSampler::facing_fraction(const Vec3& wi) const {
    require_unit(wi, "hammon sampler: wi");
    const double sin_i = std::hypot(wi.x(), wi.y());
    if (sin_i == 0.0) return wi.z() > 0.0 ? 1.0 : 0.0;
    // For tan(theta_m) = r, the azimuths with wi.m > 0 are cos(phi) > -mu / r, mu = cot(theta_i) (signed).
    const double mu = wi.z() / sin_i;
    // Only normals steeper than tan^2 = mu^2 can face away from (mu > 0) or towards (mu < 0) wi: where the D cos
    // mass beyond mu^2 is below double's resolution (wi within ~1e-6 degrees of the normal for alpha = 0.3), Z is 1 or
    // 0 (when that mass is 0) exactly, and the quadrature below would have to find the lobe 700 e-folds from its split.
    const double beyond = dcos_.sf(mu * mu);
    if (mu > 0.0 ? beyond < 1e-17 : beyond == 0.0) return mu > 0.0 ? 1.0 : 0.0;
    auto h = [&](double s) {
        const double c = std::clamp(-mu / std::sqrt(s), -1.0, 1.0);
        return std::acos(c) * dcos_.P22(s);  // (acos / pi) * pi P22
    };
    // Split at the kink s = mu^2, kept inside [1e-300, 1e300] (mu = 5.7e201 at theta_i = 1e-200 degrees).
    return integrate_log_axis(h, {}, mu != 0.0 ? std::clamp(mu * mu, 1e-300, 1e300) : 1.0);
}

}  // namespace smithlab
