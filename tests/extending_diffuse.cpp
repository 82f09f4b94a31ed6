// The worked example of docs/extending.md, "A new diffuse model": Minnaert's model (experiments/plugin_example/
// minnaert.hpp, the plug-in example's), checked against its closed-form directional albedo and Lambert, registered
// after the built-in models, and exported as GLSL. docs/update_docs.py quotes the part between the [docs: ...]
// markers into docs/extending.md, and its --check mode (ctest docs_up_to_date) fails when the two differ.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <smithlab/smithlab.hpp>
#include <string>

#include "minnaert.hpp"

namespace {

namespace fit = smithlab::fit;
using smithlab::Vec3;

// The directional albedo of f at cos(theta_i) = mu_i by the midpoint rule in (mu_o, phi_o): n x 2n cells.
double albedo_by_midpoints(const fit::DiffuseModel& m, double s, double alpha, double mu_i, int n) {
    const Vec3 wi(std::sqrt(1.0 - mu_i * mu_i), 0.0, mu_i);
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const double mu = (i + 0.5) / n, phi = (j + 0.5) * std::numbers::pi / n, r = std::sqrt(1.0 - mu * mu);
            sum += m.f(wi, Vec3(r * std::cos(phi), r * std::sin(phi), mu), alpha, 0.8, &s) * mu;
        }
    return sum * (1.0 / n) * (std::numbers::pi / n);
}

}  // namespace

// [docs: minnaert-test]
TEST_CASE("a diffuse model of one's own: its albedo, its registration and its GLSL", "[extending][diffuse]") {
    const fit::DiffuseModel m = minnaert_model();
    // Its directional albedo is 0.8 mu_i^(k - 1) at albedo 0.8 (minnaert.hpp), by a quadrature written here and by
    // the fitter's; k = 1 (s = 0) is Lambert.
    for (double s : {-0.4, 0.0, 0.7})
        for (double mu_i : {1.0, 0.5, 0.1}) {
            const double k = 1.0 + s * 0.5, exact = 0.8 * std::pow(mu_i, k - 1.0);
            CHECK(albedo_by_midpoints(m, s, 0.5, mu_i, 400) == Approx(exact).epsilon(1e-3));
            CHECK(fit::model_albedo(m, {s}, 0.5, std::acos(mu_i) * 180.0 / std::numbers::pi, 0.8) ==
                  Approx(exact).epsilon(1e-4));
        }
    const Vec3 wi(0.6, 0.0, 0.8), wo(-0.28, 0.0, 0.96);
    const double s0 = 0.0;
    CHECK(m.f(wi, wo, 0.5, 0.8, &s0) == Approx(fit::lambert(0.8)).epsilon(1e-15));

    // Registered after the built-in models; the commands then list, fit and export it (the plug-in example).
    smithlab::NdfRegistry registry;  // the built-in materials and diffuse models, to which a program adds its own
    registry.diffuse_models().add(minnaert_model());
    const fit::DiffuseRegistry& models = registry.diffuse_models();
    CHECK(&models.at("minnaert") == &models.list().back());
    CHECK(models.names().ends_with(", smithlab-2026, minnaert"));

    // Its GLSL: the function the fit exports calls Minnaert's at the fitted constant.
    const double fitted = 0.25, stderr_ = 0.01;
    const fit::ShaderModel shader{"minnaert-fitted", "ggx", &models.at("minnaert"), {&fitted, 1}, {&stderr_, 1}};
    const std::string library = fit::glsl_library({&shader, 1});
    CHECK_THAT(library, Catch::Contains("float minnaert_brdf(vec3 L, vec3 V, vec3 N, float k, float albedo)"));
    CHECK_THAT(library,
               Catch::Contains("float smithlab_minnaert_fitted_ggx(vec3 L, vec3 V, vec3 N, float alpha, "
                               "float albedo)\n{\n    return minnaert_brdf(L, V, N, 1.0 + 0.25 * alpha, "
                               "albedo);\n}\n"));
}
// [end docs]

// The exported library through the reference compiler, where it is installed.
TEST_CASE("a diffuse model of one's own: its GLSL compiles", "[extending][diffuse]") {
    const std::string validator = "/usr/bin/glslangValidator";
    if (!std::filesystem::exists(validator)) {
        WARN("no " << validator << " (Debian: glslang-tools): the GLSL is not compiled");
        return;
    }
    const fit::DiffuseModel m = minnaert_model();
    const double fitted = 0.25;
    const fit::ShaderModel shader{"minnaert-fitted", "ggx", &m, {&fitted, 1}, {}};
    const std::filesystem::path frag = std::filesystem::temp_directory_path() / "smithlab_extending_diffuse.frag";
    std::ofstream(frag) << "#version 330 core\n"
                        << fit::glsl_library({&shader, 1})
                        << "uniform vec3 L;\nuniform vec3 V;\nuniform float alpha;\nout vec4 color;\n"
                           "void main()\n{\n    color = vec4(smithlab_minnaert_fitted_ggx(L, V, vec3(0, 0, 1), "
                           "alpha, 0.5));\n}\n";
    CHECK(std::system((validator + " " + frag.string() + " > /dev/null 2>&1").c_str()) == 0);
    std::filesystem::remove(frag);
}
