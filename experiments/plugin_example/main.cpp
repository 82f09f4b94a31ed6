// Plugging a new NDF into smithlab: write D(cos theta_m), register it, and the whole command line is yours:
//     plugin_example check --ndf 'myggx(alpha=0.3)'
//     plugin_example trace --ndf 'myggx(alpha=0.3)' --material mirror
//     plugin_example fit SCENE.toml            ([[ndf]] family = "myggx": swept over the training set's alpha)
// Here GGX by hand (Walter 2007 eq. 33), D alone: smithlab derives its Lambda (quadrature, then a table for the walk),
// its samplers and its checks, and walks it as its own type (no virtual call per bounce). And a diffuse model of its
// own, Minnaert's (minnaert.hpp): `plugin_example fit` fits it beside the built-in ones and exports its GLSL.
#include <numbers>
#include <smithlab/cli.hpp>
#include <smithlab/smithlab.hpp>

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
    smithlab::fit::DiffuseRegistry models = smithlab::fit::builtin_diffuse_registry();
    models.add(minnaert_model());
    return smithlab::run_cli(argc, argv, registry, models);
}
