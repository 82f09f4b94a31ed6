// smithlab/walk/microsurface.hpp -- the Smith microsurface a walk runs on: an NDF's Lambda and visible normals, and a
// height law. Built once per cell (its tables included) and read-only afterwards, so any number of threads share it.
//
// A ray at height h travelling along w (a unit vector; w.z > 0 going up) next meets the surface where
//     C1(h') = C1(h) S^(-1 / Lambda(w)),  S uniform in (0, 1],
// unless it goes up and S <= C1(h)^Lambda(w), in which case it escapes (Hammon 2017 appendix, "Intersection
// distance" and "Escaping rays": the survival function S = (C1(h0) / C1(h))^Lambda is inverted; Heitz, Hanika, d'Eon,
// Dachsbacher 2016, sec. 4, alg. 2). Lambda of a downward direction is Smith's Lambda(-mu) = -1 - Lambda(mu) (< 0,
// so h' < h: it always hits) or Hammon's symmetric -Lambda(mu) (smith.hpp, Downward). A horizontal ray (mu = 0,
// Lambda = inf) hits at its own height, the mu -> 0 limit Hammon derives ("Handling mu = 0"). The hit normal is a
// visible normal of -w, drawn from <-w.m>^+ D(m) / A(-w) over the whole sphere of -w (Heitz et al. 2016, sec. 4.2).
#pragma once

#include <cmath>

#include "smithlab/geometry.hpp"
#include "smithlab/smith.hpp"
#include "smithlab/visible_normals.hpp"
#include "smithlab/walk/heights.hpp"

namespace smithlab::walk {

struct MicrosurfaceOptions {
    Downward downward = Downward::smith;
};

template <Ndf N, class Heights = UniformHeights>
class Microsurface {
public:
    explicit Microsurface(const N& ndf, const MicrosurfaceOptions& opts = {}) : normals_(ndf), opts_(opts) {}

    // Lambda of a travel direction w: Lambda(mu) for mu = cot(theta_w) >= 0, the downward convention below.
    double Lambda(const Vec3& w) const {
        const double mu = w.z() / std::sqrt(w.x() * w.x() + w.y() * w.y());  // +-inf straight up or down
        if (mu >= 0.0) return normals_.Lambda()(mu);
        return downward_Lambda(normals_.Lambda()(-mu), opts_.downward);
    }

    // Moves h to the next intersection along w and returns true, or returns false when the ray escapes.
    // S in (0, 1]. Worked in ln C1, so that neither S^(-1/Lambda) nor C1^Lambda over- or underflows.
    bool next_height(const Vec3& w, double& h, double S) const {
        const double L = Lambda(w);
        if (L == INFINITY) return true;  // horizontal: it hits at its own height
        const double ln_c0 = ln_C1(h), ln_S = std::log(S);
        if (L >= 0.0 && ln_S <= L * ln_c0) return false;
        const double ln_c = ln_c0 - ln_S / L;
        if (ln_c <= 0.0) h = Heights::invC1(std::exp(ln_c));  // else S = 1 with L = -0: it stays (measure zero)
        return true;
    }

    // The probability that a ray leaving height h along wo escapes: C1(h)^Lambda(wo) upward, 0 downward
    // (Hammon 2017, "Solving for G1 given S"; Heitz et al. 2016, G_1(w, h)).
    double escape(const Vec3& wo, double h) const {
        if (!(wo.z() > 0.0)) return 0.0;
        const double L = Lambda(wo);
        return L == 0.0 ? 1.0 : std::exp(L * ln_C1(h));
    }

    // A normal drawn from the visible normals of v: the normal a ray travelling along -v hits, and the law the
    // phase functions integrate over.
    template <class G>
    Vec3 visible_normal(const Vec3& v, G& g) const {
        return normals_.sample(v, g);
    }

    const VisibleNormals<N>& normals() const { return normals_; }

private:
    // ln C1(h), kept finite at the bottom of the law (C1 = 0) so that products with Lambda stay numbers.
    static double ln_C1(double h) {
        constexpr double ln_smallest = -744.44007192138126;  // ln of the smallest denormal
        const double c = Heights::C1(h);
        return c > 0.0 ? std::log(c) : ln_smallest;
    }

    VisibleNormals<N> normals_;
    MicrosurfaceOptions opts_;
};

}  // namespace smithlab::walk
