// Plugging a new NDF and a new facet material into smithlab: write D(cos theta_m), write how a facet scatters,
// register both, and the whole command line is yours:
//     plugin_example check --ndf 'myggx(alpha=0.3)'
//     plugin_example trace --ndf 'myggx(alpha=0.3)' --material 'coated-lambert(r=0.04)'
//     plugin_example fit SCENE.toml            ([[ndf]] family = "myggx": swept over the training set's alpha)
// Here GGX by hand (Walter 2007 eq. 33), D alone: smithlab derives its Lambda (quadrature, then a table for the walk),
// its samplers and its checks, and walks it as its own type (no virtual call per bounce). The material: Lambertian
// facets under a clear coat of constant reflectance r. And a diffuse model of its own, Minnaert's (minnaert.hpp):
// `plugin_example fit` fits it beside the built-in ones and exports its GLSL.
#include <numbers>
#include <smithlab/cli.hpp>
#include <smithlab/gtr.hpp>

#include "minnaert.hpp"

struct MyGgx {
    double alpha;
    double D(double c) const {
        if (c <= 0.0) return 0.0;
        const double c2 = c * c, tan2 = (1.0 - c2) / c2;
        const double s = alpha * alpha + tan2;
        return alpha * alpha / (std::numbers::pi * c2 * c2 * s * s);
    }
};

// A facet reflects specularly with probability r, else diffusely, albedo / pi about its normal (a Lambertian base
// under a coat whose reflectance is r at every angle): facet BRDF r spec + (1 - r) albedo / pi, symmetric in wi, wo.
struct CoatedLambert {
    double r, albedo;
    static constexpr bool reciprocal = true;
    static smithlab::walk::MaterialInfo info() {
        return {"coated-lambert",
                {{"r", 0.04, 0.0, 1.0}, {"albedo", 1.0, 0.0, 1.0}},
                "Lambertian facets under a clear coat of constant reflectance r (both in [0, 1])"};
    }
    static CoatedLambert make(const smithlab::walk::MaterialParams& p) { return {p.at("r"), p.at("albedo")}; }
    smithlab::NdfSpec spec() const { return {"coated-lambert", {{"r", r}, {"albedo", albedo}}}; }
    bool has_diffuse() const { return albedo > 0.0; }

    template <class G>
    smithlab::walk::Scatter sample(const smithlab::Vec3& wi, const smithlab::Vec3& m, G& g) const {
        if (smithlab::uniform01(g) < r) return smithlab::walk::Mirror{}.sample(wi, m, g);
        return {smithlab::walk::Lambert{1.0}.sample(wi, m, g).wo, albedo, true};
    }
    template <class Microsurface, class G>
    smithlab::walk::Phase phase(const Microsurface& ms, const smithlab::Vec3& wi, const smithlab::Vec3& wo,
                                G& g) const {
        const smithlab::walk::Phase mirror = smithlab::walk::Mirror{}.phase(ms, wi, wo, g);
        const smithlab::walk::Phase lambert = smithlab::walk::Lambert{albedo}.phase(ms, wi, wo, g);
        return {r * mirror.specular, (1.0 - r) * lambert.diffuse};
    }
};

int main(int argc, char** argv) {
    smithlab::NdfRegistry registry = smithlab::builtin_registry();
    registry.add({.name = "myggx",
                  .parameters = {"alpha"},
                  .description = "GGX written by hand, D only",
                  .examples = {"myggx(alpha=0.05)", "myggx(alpha=0.3)", "myggx(alpha=0.8)"}},
                 [](const smithlab::NdfParams& p) {
                     const double alpha = p.at("alpha");
                     smithlab::require(alpha >= 0.01 && alpha <= 1.0, "myggx: alpha", "in [0.01, 1]", alpha);
                     return MyGgx{alpha};
                 });
    // Walked as its own type on every built-in NDF and on myggx.
    registry.materials().add<CoatedLambert>(smithlab::builtin_ndf_types{} + smithlab::NdfTypes<MyGgx>{});
    registry.diffuse_models().add(minnaert_model());
    return smithlab::run_cli(argc, argv, registry);
}
