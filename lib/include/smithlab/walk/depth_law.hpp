/// @file
/// smithlab/walk/depth_law.hpp -- the law of a walk's depth at its next hit given only the directions it travelled:
/// a sum of exponentials, moved along in closed form (the position-free estimator, position_free.hpp).
///
/// Depth t = -ln C1(h) >= 0 (0 at the top of the height law; microsurface.hpp carries u = ln C1 = -t). Under Smith's
/// downward convention the walk's height steps are exponential in t (Heitz, Hanika, d'Eon, Dachsbacher 2016, sec. 4,
/// alg. 2; Hammon 2017 appendix, "Intersection distance"): a ray travelling down along w goes from t to t + X, X ~
/// Exp(a), a = -Lambda(w) = 1 + Lambda(-w) >= 1; one travelling up, rate l = Lambda(w) >= 0, to t - X, X ~ Exp(l), and
/// escapes where that is below 0. So given the directions, the depths of the hits are a Markov chain, and the chance to
/// reach hit k at depth t is a sub-density p_k(t) = sum_i c_i e^{-r_i t} (Bitterli and d'Eon 2022, "A Position-Free
/// Path Integral for Homogeneous Slabs and Multiple Scattering on Smith Microfacets", CGF 41(4), sec. 5: the collision
/// distances integrated out of a path of directions; here in the depth of the height law, for any NDF's Lambda):
///   (1) from above, the first hit:  p_1(t) = a_0 e^{-a_0 t}, a_0 = 1 + Lambda(wi);
///   (2) up at rate l:  c e^{-r t} -> c l / (r + l) e^{-r t}, from int_t^inf c e^{-r s} l e^{-l (s-t)} ds;
///   (3) down at rate a:  c e^{-r t} -> c a / (a - r) (e^{-r t} - e^{-a t}), from int_0^t c e^{-r s} a e^{-a (t-s)} ds;
///   (4) reaching the next hit:  int p = sum_i c_i / r_i;
///   (5) escaping toward wo (up, Lambda(wo) = L) from the hit:  int p e^{-L t} dt = sum_i c_i / (r_i + L);
///   (6) escaping on the other side, where C1 is 1 - e^{-t}:  int p (1 - e^{-t})^L dt = sum_i c_i B(r_i, L + 1).
/// (2) keeps the rates; (3) adds one, so the terms are one more than the downward steps. (3) cancels where a is near
/// an r_i, and a sum of many terms can hold large coefficients of both signs: a move that would make the sum's
/// magnitude sum_i |c_i| / r_i more than 1e6 times its value (which leaves its value ~1e-10 relative), or need more
/// than max_terms terms, is refused (down() returns false), and the walk then draws its depth from the law (sample())
/// and goes on as the height walk does. Nothing here allocates, throws or calls a virtual function.
#pragma once

#include <array>
#include <cmath>

#include "smithlab/rng.hpp"

namespace smithlab::walk {

/// The sub-density sum_i c_i e^{-r_i t} of a walk's depth at its next hit (the file comment).
class DepthLaw {
public:
    /// The most terms it holds: one more than the downward steps since the first hit.
    static constexpr int max_terms = 16;
    /// The most that sum_i `|`c_i`|` / r_i may exceed the mass (4) by.
    static constexpr double max_condition = 1e6;

    /// The first hit of a ray from above with downward rate a0 = 1 + Lambda(wi), eq. (1).
    explicit DepthLaw(double a0) : n_(1) {
        c_[0] = a0;
        r_[0] = a0;
    }

    /// Eq. (5): the chance to escape from the hit along a direction of Lambda L >= 0 (1 at L = 0; inf: 0).
    double escape(double L) const {
        double e = 0.0;
        for (int i = 0; i < n_; ++i) e += c_[i] / (r_[i] + L);
        return e;
    }
    /// Eq. (6): the chance to escape on the other side along a direction of Lambda L >= 0 there, the height seen from
    /// below (C1 -> 1 - C1: microsurface.hpp, other_side).
    double escape_other_side(double L) const {
        if (L == INFINITY) return 0.0;
        double e = 0.0;
        for (int i = 0; i < n_; ++i)
            e += c_[i] * std::exp(std::lgamma(r_[i]) + std::lgamma(L + 1.0) - std::lgamma(r_[i] + L + 1.0));
        return e;
    }
    /// Eq. (4): the chance to be at a hit at all.
    double mass() const { return escape(0.0); }

    /// Eq. (2): the ray leaves the hit upward with Lambda l >= 0 (inf: horizontal, it hits where it is); what is left
    /// is the chance to hit again.
    void up(double l) {
        if (l == INFINITY) return;
        for (int i = 0; i < n_; ++i) c_[i] *= l / (r_[i] + l);
    }
    /// Eq. (3): the ray leaves downward with rate a = -Lambda(w) >= 1 (inf: horizontal). false, the law unchanged,
    /// where the move would need more terms than max_terms or leave the sum ill-conditioned (the file comment).
    bool down(double a) {
        if (a == INFINITY) return true;
        if (n_ == max_terms) return false;
        std::array<double, max_terms> c;
        double last = 0.0, magnitude = 0.0, mass = 0.0;
        for (int i = 0; i < n_; ++i) {
            c[i] = c_[i] * a / (a - r_[i]);
            last -= c[i];
            magnitude += std::abs(c[i]) / r_[i];
            mass += c[i] / r_[i];
        }
        magnitude += std::abs(last) / a;
        mass += last / a;
        if (!(magnitude <= max_condition * mass)) return false;  // also NaN, inf: a at an r_i
        for (int i = 0; i < n_; ++i) c_[i] = c[i];
        c_[n_] = last;
        r_[n_] = a;
        ++n_;
        return true;
    }
    /// Multiplies the law by s > 0 (a Russian roulette's survivors).
    void scale(double s) {
        for (int i = 0; i < n_; ++i) c_[i] *= s;
    }

    /// A depth drawn from p / mass(): the root of sum_i c_i / r_i e^{-r_i t} = (1 - U) mass(), by Newton's method kept
    /// inside a bracket that bisection narrows (the tail sum decreases from mass() at t = 0 to 0).
    template <class G>
    double sample(G& g) const {
        const double target = (1.0 - uniform01(g)) * mass();
        double lo = 0.0, hi = 1.0;
        while (tail(hi) > target && hi < 1e3) hi *= 2.0;
        double t = 0.5 * (lo + hi);
        for (int k = 0; k < 100 && hi - lo > 1e-15 * hi; ++k) {
            const double f = tail(t) - target;
            (f > 0.0 ? lo : hi) = t;
            const double next = t + f / density(t);  // d tail / dt = -p
            t = next > lo && next < hi ? next : 0.5 * (lo + hi);
        }
        return t;
    }

    int terms() const { return n_; }  ///< the number of exponentials

private:
    double tail(double t) const {  // int_t^inf p
        double s = 0.0;
        for (int i = 0; i < n_; ++i) s += c_[i] / r_[i] * std::exp(-r_[i] * t);
        return s;
    }
    double density(double t) const {  // p(t)
        double s = 0.0;
        for (int i = 0; i < n_; ++i) s += c_[i] * std::exp(-r_[i] * t);
        return s;
    }

    std::array<double, max_terms> c_{}, r_{};
    int n_;
};

}  // namespace smithlab::walk
