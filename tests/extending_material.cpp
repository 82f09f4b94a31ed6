// The worked example of docs/extending.md, "A new facet material": a tinted mirror, written as a type the walk takes
// directly (walk/walk.hpp and walk/trace.hpp are templates on the material), and checked here by a white furnace and
// by what each reflection must keep. docs/update_docs.py quotes the part between the [docs: ...] markers into
// docs/extending.md, and its --check mode (ctest docs_up_to_date) fails when the two differ.
#include <catch2/catch.hpp>
#include <cmath>
#include <smithlab/gtr.hpp>
#include <smithlab/walk/trace.hpp>

// [docs: tinted-mirror]
// Mirror facets that keep the fraction `tint` of the light at every reflection: a conductor whose Fresnel
// reflectance is the constant tint. sample() and phase() reuse walk::Mirror and scale its weight; info(), make() and
// spec() are its registration.
struct TintedMirror {
    double tint;  // in [0, 1]
    // Its registration: the spec "tinted-mirror(tint=1)" and its range, and back.
    static smithlab::walk::MaterialInfo info() {
        return {"tinted-mirror", {{"tint", 1.0, 0.0, 1.0}}, "mirror facets keeping the fraction tint (in [0, 1])"};
    }
    static TintedMirror make(const smithlab::walk::MaterialParams& p) { return {p.at("tint")}; }
    smithlab::NdfSpec spec() const { return {"tinted-mirror", {{"tint", tint}}}; }

    template <class G>
    smithlab::walk::Scatter sample(const smithlab::Vec3& wi, const smithlab::Vec3& m, G& g) const {
        smithlab::walk::Scatter s = smithlab::walk::Mirror{}.sample(wi, m, g);  // the mirror direction, weight 1
        s.weight = tint;
        return s;
    }
    template <class Microsurface, class G>
    smithlab::walk::Phase phase(const Microsurface& ms, const smithlab::Vec3& wi, const smithlab::Vec3& wo,
                                G& g) const {
        smithlab::walk::Phase p = smithlab::walk::Mirror{}.phase(ms, wi, wo, g);  // F D(h) / (4 A(wi)) with F = 1
        p.specular *= tint;
        return p;
    }
};
// [end docs]

namespace {

namespace walk = smithlab::walk;

smithlab::Vec3 from_theta_deg(double theta_deg) {
    const double t = theta_deg * std::acos(-1.0) / 180.0;
    return {std::sin(t), 0.0, std::cos(t)};
}

}  // namespace

// [docs: tinted-mirror-test]
TEST_CASE("a tinted mirror: a white furnace at tint 1 and tint^k of the mirror at order k", "[extending][walk]") {
    const walk::Microsurface ms(smithlab::ggx(0.5));  // the concrete NDF type: no virtual call in the walk
    walk::CellRequest r;
    r.wi = from_theta_deg(60.0);
    r.walks = 20'000;
    r.seed = 11;

    // White furnace: with tint 1 every walk leaves with all its energy.
    const walk::CellResult white = walk::trace_cell(ms, TintedMirror{1.0}, r);
    CHECK(white.albedo.capped == 0);
    CHECK(white.albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all).value ==
          Approx(1.0).margin(1e-12));

    // Walk k draws the same numbers for any facet weight, so the light of order k is tint^k times the mirror's.
    const double tint = 0.6;
    const walk::CellResult mirror = walk::trace_cell(ms, walk::Mirror{}, r);
    const walk::CellResult tinted = walk::trace_cell(ms, TintedMirror{tint}, r);
    for (int order = 0; order < 3; ++order) {  // order bins 1, 2, 3
        const double m = mirror.albedo.albedo(walk::Hemisphere::all, order, walk::Component::all).value;
        const double t = tinted.albedo.albedo(walk::Hemisphere::all, order, walk::Component::all).value;
        INFO("order " << order + 1);
        CHECK(m > 0.0);
        CHECK(t == Approx(std::pow(tint, order + 1) * m).epsilon(1e-12));
    }
    const double m4 = mirror.albedo.albedo(walk::Hemisphere::all, 3, walk::Component::all).value;
    const double t4 = tinted.albedo.albedo(walk::Hemisphere::all, 3, walk::Component::all).value;
    CHECK(t4 > 0.0);
    CHECK(t4 <= std::pow(tint, 4) * m4 * (1.0 + 1e-12));  // orders 4+: tint^4 or less

    // The eval estimator (next-event estimation through phase()): the same relation, order by order.
    walk::EvalRequest e;
    e.wi = r.wi;
    e.wo = smithlab::Vec3(-0.5, 0.3, std::sqrt(1.0 - 0.25 - 0.09));
    e.walks = 20'000;
    const walk::EvalTally em = walk::eval_cell(ms, walk::Mirror{}, e);
    const walk::EvalTally et = walk::eval_cell(ms, TintedMirror{tint}, e);
    for (int order = 0; order < 3; ++order) {
        INFO("eval, order " << order + 1);
        CHECK(em.value(order, walk::Component::all).value > 0.0);
        CHECK(et.value(order, walk::Component::all).value ==
              Approx(std::pow(tint, order + 1) * em.value(order, walk::Component::all).value).epsilon(1e-12));
    }
}
// [end docs]

// [docs: tinted-mirror-registered]
TEST_CASE("a tinted mirror registered by name: every command's surfaces walk it as its own type", "[extending][walk]") {
    smithlab::NdfRegistry registry = smithlab::builtin_registry();
    registry.materials().add<TintedMirror>(smithlab::builtin_ndf_types{});  // one line: now any --material can name it
    const walk::Material tinted = registry.materials().make("tinted-mirror(tint=0.6)");
    CHECK(tinted.spec() == "tinted-mirror(tint=0.6)");
    CHECK_THROWS_WITH(registry.materials().make("tinted-mirror(tint=2)"), Catch::Contains("tint"));

    // Through the type-erased surface a command holds: the same bits as the walk on the concrete types.
    const smithlab::AnyNdf ggx = registry.make("ggx(alpha=0.5)");
    walk::CellRequest r;
    r.wi = from_theta_deg(60.0);
    r.walks = 4'096;
    const walk::CellPartial erased = smithlab::make_surface(ggx)->trace_block(tinted, r, 0);
    const walk::CellPartial direct = walk::trace_block(walk::Microsurface(smithlab::ggx(0.5)), TintedMirror{0.6}, r, 0);
    CHECK(erased.albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all).value ==
          direct.albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all).value);
}
// [end docs]

TEST_CASE("a registered material on an NDF type its registration did not list: walked on the NDF erased",
          "[extending][walk]") {
    smithlab::NdfRegistry registry = smithlab::builtin_registry();
    registry.materials().add<TintedMirror>(smithlab::NdfTypes<>{});  // no NDF type listed: every NDF erased
    const walk::Material tinted = registry.materials().make("tinted-mirror(tint=0.6)");
    walk::CellRequest r;
    r.wi = from_theta_deg(45.0);
    r.walks = 20'000;
    r.seed = 5;
    const walk::Estimate by_erased = smithlab::make_surface(registry.make("ggx(alpha=0.5)"))
                                         ->trace_block(tinted, r, 0)
                                         .albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
    // The concrete walk with other random numbers (another seed): the same albedo within the errors.
    r.seed = 6;
    const walk::Estimate by_type = walk::trace_block(walk::Microsurface(smithlab::ggx(0.5)), TintedMirror{0.6}, r, 0)
                                       .albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
    INFO(by_erased.value << " +- " << by_erased.stderr_ << " vs " << by_type.value << " +- " << by_type.stderr_);
    CHECK(by_erased.value < 0.9);  // tint 0.6 absorbs: not the white furnace
    CHECK(std::abs(by_erased.value - by_type.value) < 4.0 * std::hypot(by_erased.stderr_, by_type.stderr_));
}
