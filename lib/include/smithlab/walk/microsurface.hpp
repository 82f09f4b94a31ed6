/// @file
/// smithlab/walk/microsurface.hpp -- the Smith microsurface a walk runs on: an NDF's Lambda and visible normals, and a
/// height law. Built once per cell (its tables included) and read-only afterwards, so any number of threads share it.
///
/// A ray at height h travelling along w (a unit vector; w.z > 0 going up) next meets the surface where
///     C1(h') = C1(h) S^(-1 / Lambda(w)),  S uniform in (0, 1],
/// unless it goes up and S <= C1(h)^Lambda(w), in which case it escapes (Hammon 2017 appendix, "Intersection
/// distance" and "Escaping rays": the survival function S = (C1(h0) / C1(h))^Lambda is inverted; Heitz, Hanika, d'Eon,
/// Dachsbacher 2016, sec. 4, alg. 2). Lambda of a downward direction is Smith's Lambda(-mu) = -1 - Lambda(mu) (< 0,
/// so h' < h: it always hits) or Hammon's symmetric -Lambda(mu) (smith.hpp, Downward). A horizontal ray (mu = 0,
/// Lambda = inf) hits at its own height, the mu -> 0 limit Hammon derives ("Handling mu = 0").
///
/// The height the walk carries (walk.hpp's h: INFINITY above the surface, then whatever next_height leaves): the law
/// enters only through C1 (heights.hpp), so for UniformHeights it is carried as u = ln C1(h) itself, where a step is
/// u' = u - ln S / Lambda and an upward ray escapes when u' >= 0: one log and no exp per step. Any other law
/// (GaussianHeights: the check that the law does not matter) is carried as the height, through C1 and its inverse.
/// other_side(h) is the same point seen from the other side of the surface (two-sided materials: walk.hpp negates the
/// frame there): -h for a height (every law here is symmetric), ln(1 - e^u) for u (C1 -> 1 - C1).
///
/// The hit normal (HitNormal): by default a visible normal of v = -w, drawn from <v.m>^+ D(m) / A(v) over the whole
/// sphere of v (Heitz et al. 2016, sec. 4.2), what the Smith derivation implies and the law the phase functions of
/// facets.hpp integrate over; or Hammon 2017's ("Intersection normal"): D(m) cos(theta_m) restricted to the normals
/// facing the ray, v.m > 0 (dcos_law.hpp, sample_hammon_normal, on the D cos law the visible normals already hold:
/// nothing is built for it). Hammon's is for the sample estimator only: eval_walk refuses it (require_eval_normals).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "smithlab/dcos_law.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/smith.hpp"
#include "smithlab/visible_normals.hpp"
#include "smithlab/walk/heights.hpp"

namespace smithlab::walk {

/// visible: a visible normal of -T (the default); hammon_dcos: D cos restricted to T.m < 0 (Hammon 2017).
enum class HitNormal { visible, hammon_dcos };

/// The conventions of a microsurface: Lambda of a downward direction (smith.hpp, Downward) and the law of the hit
/// normal.
struct MicrosurfaceOptions {
    /// Smith's Lambda(-mu) = -1 - Lambda(mu), or Hammon's -Lambda(mu).
    Downward downward = Downward::smith;
    /// The visible normals of the ray, or Hammon's D cos facing it.
    HitNormal hit_normal = HitNormal::visible;
};

/// input_error unless the eval estimator can run on a microsurface of these options: its phase functions (facets.hpp)
/// are densities over visible normals, so a walk whose hits draw Hammon's normals would mix two laws.
inline void require_eval_normals(const MicrosurfaceOptions& opts) {
    if (opts.hit_normal != HitNormal::visible)
        throw input_error(
            "hit normal 'hammon': the eval estimator (brdf) integrates its phase functions over visible normals; "
            "Hammon's D cos hit normals are for the sample estimator (trace)");
}

/// The Smith microsurface of an NDF N with the height law Heights: where a ray next meets it, whether it escapes, and
/// the normal it hits (the file comment).
template <Ndf N, class Heights = UniformHeights>
class Microsurface {
public:
    /// Builds the NDF's visible normals (their tables included) for the given conventions.
    explicit Microsurface(const N& ndf, const MicrosurfaceOptions& opts = {}) : normals_(ndf), opts_(opts) {}

    /// Lambda of a travel direction w: Lambda(mu) for mu = cot(theta_w) >= 0, the downward convention below. From
    /// tan^2(theta_w) (FastLambda::at_tan2: GGX's closed form without a root of mu); where tan^2 would lose digits to
    /// under- or overflow (within 1e-150 of the pole or the horizon, straight up, horizontal), from mu itself.
    double Lambda(const Vec3& w) const {
        const double t = tan2_theta(w);
        const double up = t > 1e-300 && t < 1e300 ? normals_.Lambda().at_tan2(t)
                                                  : normals_.Lambda()(std::abs(w.z()) / std::hypot(w.x(), w.y()));
        return w.z() >= 0.0 ? up : downward_Lambda(up, opts_.downward);  // -0 (horizontal) is up: inf either way
    }

    /// Moves h to the next intersection along w and returns true, or returns false when the ray escapes.
    /// S in (0, 1]. With k = -ln S / Lambda, ln C1(h') = ln C1(h) + k, and an upward ray escapes when that is >= 0
    /// (S <= C1(h)^Lambda). 1 / Lambda comes as a quotient num / den (inv_Lambda: num > 0 upward, < 0 downward), so
    /// that the escape test, -ln S num >= -ln C1(h) den, needs no division; only a ray that stays divides. Lambda = +0
    /// (num / den = inf) escapes, at S = 1 too; a horizontal ray (Lambda = inf) hits at its own height; a NaN
    /// direction stays where it is. Always inlined: the step of every walk's bounce, which GCC inlined or not by how
    /// many walks a translation unit instantiates (fresnel-diffuse and dielectric walks took 3-8 % more instructions).
    [[gnu::always_inline]] bool next_height(const Vec3& w, double& h, double S) const {
        const Quotient inv_L = inv_Lambda(w);
        if (inv_L.den == INFINITY) return true;  // horizontal (Lambda = inf): it hits at its own height
        const double e = -std::log(S);
        if constexpr (carries_ln_C1) {
            const double u0 = std::min(h, 0.0);  // h = INFINITY above the surface: C1 = 1
            if (inv_L.num > 0.0) {
                if (!(e * inv_L.num < -u0 * inv_L.den)) return false;
                const double u = u0 + e * inv_L.value();
                if (!(u < 0.0)) return false;  // only by rounding: the same test, divided
                h = u;
            } else if (const double u = u0 + e * inv_L.value(); u <= 0.0) {
                h = std::max(u, ln_smallest);  // the bottom of the law (C1 = 0), kept a number
            }                                  // else S = 1 with Lambda = -0 (NaN), or a NaN direction: it stays
            return true;
        } else {
            const double k = e * inv_L.value();
            const double c0 = Heights::C1(h);
            const bool up = inv_L.num > 0.0;
            if (c0 < 1e-290) return next_height_ln(up, k, h);
            const double c = c0 * std::exp(k);  // over- or underflows only where the answer is the same
            if (up) {
                if (!(c < 1.0)) return false;
            } else if (!(c <= 1.0)) {
                return true;
            }
            h = Heights::invC1(c);
            return true;
        }
    }

    /// The probability that a ray leaving height h along wo escapes: C1(h)^Lambda(wo) upward, 0 downward
    /// (Hammon 2017, "Solving for G1 given S"; Heitz et al. 2016, G_1(w, h)).
    double escape(const Vec3& wo, double h) const {
        if (!(wo.z() > 0.0)) return 0.0;
        const double L = Lambda(wo);
        return L == 0.0 ? 1.0 : std::exp(L * ln_C1(h));
    }

    /// The carried height of depth t = -ln C1(h) >= 0 (walk/depth_law.hpp), kept finite at the bottom of the law.
    double height_at_depth(double t) const {
        const double u = std::max(-t, ln_smallest);
        if constexpr (carries_ln_C1) return u;
        else return Heights::invC1(std::exp(u));
    }

    /// The carried height h as seen from the other side of the surface (two-sided materials). For u = ln C1 it is
    /// ln(1 - e^u), by expm1 near u = 0 and log1p below -ln 2 (Maechler 2012, "Accurately Computing
    /// log(1 - exp(-|a|))", eq. 7).
    double other_side(double h) const {
        if constexpr (carries_ln_C1) {
            const double u = std::min(h, 0.0);
            const double v = u > -std::numbers::ln2 ? std::log(-std::expm1(u)) : std::log1p(-std::exp(u));
            return std::max(v, ln_smallest);
        } else {
            return -h;
        }
    }

    /// The normal a ray travelling along -v hits, by the option's law; no_normal() (NaN) when it cannot be drawn
    /// (walk.hpp ends the walk as capped then).
    template <class G>
    Vec3 hit_normal(const Vec3& v, G& g) const {
        if (opts_.hit_normal == HitNormal::hammon_dcos) [[unlikely]]
            return sample_hammon_normal(normals_.dcos(), v, g);
        return normals_.sample(v, g);
    }

    /// A normal drawn from the visible normals of v: the law the phase functions integrate over (whatever the hit
    /// normal's option).
    template <class G>
    Vec3 visible_normal(const Vec3& v, G& g) const {
        return normals_.sample(v, g);
    }

    /// The NDF's visible normals.
    const VisibleNormals<N>& normals() const { return normals_; }
    /// The conventions it was built with.
    const MicrosurfaceOptions& options() const { return opts_; }

private:
    static constexpr bool carries_ln_C1 = std::is_same_v<Heights, UniformHeights>;
    static constexpr double ln_smallest = -744.44007192138126;  ///< ln of the smallest denormal

    /// 1 / Lambda(w) under the downward convention as a quotient (num > 0 upward, < 0 downward; den = inf
    /// horizontal, 0 straight up), by FastLambda's reciprocal forms away from the pole and the horizon, through
    /// Lambda(w) near them.
    Quotient inv_Lambda(const Vec3& w) const {
        const double d2 = w.x() * w.x() + w.y() * w.y(), az = std::abs(w.z());
        if (!(d2 > 1e-300 && az > 1e-150)) [[unlikely]] {
            const double L = Lambda(w);
            if (std::isnan(L)) return {L, L};
            return {std::signbit(L) ? -1.0 : 1.0, std::abs(L)};
        }
        const FastLambda<N>& L = normals_.Lambda();
        if (w.z() > 0.0) return L.inv_Lambda(d2, az);
        const Quotient q = opts_.downward == Downward::smith ? L.inv_1p_Lambda(d2, az) : L.inv_Lambda(d2, az);
        return {-q.num, q.den};
    }

    /// next_height for a height near the bottom of its law (C1(h) < 1e-290, where C1 e^k could be < 1 with e^k = inf),
    /// in ln C1 (Hammon 2017 appendix, "Intersection distance", as written).
    static bool next_height_ln(bool up, double k, double& h) {
        const double ln_c = ln_C1(h) + k;
        if (up && !(ln_c < 0.0)) return false;
        if (ln_c <= 0.0) h = Heights::invC1(std::exp(ln_c));  // else S = 1 with L = -0: it stays (measure zero)
        return true;
    }

    /// ln C1 of the carried height, kept finite at the bottom of the law (C1 = 0) so that products with Lambda stay
    /// numbers.
    static double ln_C1(double h) {
        if constexpr (carries_ln_C1) {
            return std::min(h, 0.0);
        } else {
            const double c = Heights::C1(h);
            return c > 0.0 ? std::log(c) : ln_smallest;
        }
    }

    VisibleNormals<N> normals_;
    MicrosurfaceOptions opts_;
};

}  // namespace smithlab::walk
