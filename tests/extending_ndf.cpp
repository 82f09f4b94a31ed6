// The worked example of docs/extending.md, "A new NDF in C++": an NDF written as D alone, through the library calls
// (no registration), checked against GGX's closed forms, which the D-only route never sees. docs/update_docs.py quotes
// the part between the [docs: ...] markers into docs/extending.md (ctest docs_up_to_date fails when they differ).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <smithlab/smithlab.hpp>

namespace {

// GGX written by hand, D alone (Walter 2007 eq. 33).
struct MyGgx {
    double alpha;
    double D(double c) const {
        if (c <= 0.0) return 0.0;
        const double c2 = c * c, tan2 = (1.0 - c2) / c2;
        const double s = alpha * alpha + tan2;
        return alpha * alpha / (std::numbers::pi * c2 * c2 * s * s);
    }
};

}  // namespace

TEST_CASE("an NDF written as D alone: Lambda, G2, visible normals and a table against GGX's closed forms",
          "[extending][smith]") {
    const smithlab::Ggx ggx = smithlab::ggx(0.3);
    // [docs: d-only-calls]
    double l = smithlab::Lambda(MyGgx{0.3}, 0.5);    // mu = cot(theta_v); by quadrature: no closed form
    double g2 = smithlab::G2(MyGgx{0.3}, 0.5, 2.0);  // height-correlated
    smithlab::Rng rng = smithlab::make_rng(7);
    smithlab::VisibleNormalSampler vis(MyGgx{0.3});  // its tables: milliseconds, once
    smithlab::NormalSample v = vis.sample(smithlab::direction_from_theta_deg(60), rng);
    smithlab::LambdaTable fast = smithlab::tabulate_Lambda(MyGgx{0.3});  // Lambda in ~20 ns
    // [end docs]
    CHECK(l == Approx(ggx.Lambda(0.5)).epsilon(1e-10));
    CHECK(g2 == Approx(1.0 / (1.0 + ggx.Lambda(0.5) + ggx.Lambda(2.0))).epsilon(1e-10));
    CHECK(std::abs(v.m.norm() - 1.0) < 1e-12);
    CHECK(v.m.z() > 0.0);
    CHECK(v.pdf == Approx(vis.pdf(smithlab::direction_from_theta_deg(60), v.m)).epsilon(1e-9));
    for (double mu : {1e-3, 0.1, 0.5, 2.0, 100.0}) {
        INFO("mu " << mu);
        CHECK(fast.Lambda(mu) == Approx(ggx.Lambda(mu)).epsilon(1e-5));
    }
}
