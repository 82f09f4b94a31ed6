// Fits at tiny albedos: the same constants and standard errors as at a larger albedo where the data determine every
// constant; a fit failure naming the constant where they do not; albedos below 1e-100 refused at scene read.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/fit/diffuse_models.hpp"
#include "smithlab/fit/fit_model.hpp"

using namespace smithlab;
using Catch::Matchers::Contains;

namespace {

// Data made by the model itself (its value at albedo a is c1 a + c2 a^2 per point) with 20 % noise per walk: per
// point, walks whose k = 1 and k = 2 values are c1 and c2 times (1 + noise).
std::vector<fit::DataPoint> model_data(const fit::DiffuseModel& m, std::uint64_t seed) {
    std::mt19937_64 g(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::vector<fit::DataPoint> pts;
    for (double alpha : {0.1, 0.3, 0.6, 1.0})
        for (double ti : {0.0, 30.0, 60.0, 80.0})
            for (double to : {10.0, 40.0, 70.0})
                for (double phi : {0.0, 90.0, 180.0}) {
                    fit::DataPoint p{alpha, {ti, to, phi}, {}};
                    const Vec3 wi = p.dir.wi(), wo = p.dir.wo();
                    const double f1 = m.f(wi, wo, alpha, 1.0, m.published.data()) * wo.z();
                    const double fh = m.f(wi, wo, alpha, 0.5, m.published.data()) * wo.z();
                    const double c2 = 2.0 * f1 - 4.0 * fh, c1 = f1 - c2;
                    for (int w = 0; w < 50; ++w) {
                        fit::Split x{};
                        x[1] = c1 * (1.0 + 0.2 * noise(g));
                        x[2] = c2 * (1.0 + 0.2 * noise(g));
                        p.moments.add(x);
                    }
                    pts.push_back(p);
                }
    return pts;
}

}  // namespace

TEST_CASE("fit: at albedo 1e-12 a model linear in small albedos gets the constants and standard errors of 1e-6",
          "[checks][fit]") {
    for (const char* name : {"fujii", "eon", "oren-nayar"}) {
        const fit::DiffuseModel& m = fit::find_diffuse_model(name);
        const std::vector<fit::DataPoint> pts = model_data(m, 7);
        const fit::LeastSquaresFit big = fit::fit_model(m, {pts, {1e-6}, 0.02, {}}, "albedo 1e-6");
        const fit::LeastSquaresFit tiny = fit::fit_model(m, {pts, {1e-12}, 0.02, {}}, "albedo 1e-12");
        for (std::size_t i = 0; i < m.parameters.size(); ++i) {
            INFO(name << " " << m.parameters[i] << ": " << tiny.params[i] << " +- " << tiny.stderr_[i] << " against "
                      << big.params[i] << " +- " << big.stderr_[i]);
            CHECK(big.stderr_[i] > 0.0);
            CHECK(tiny.params[i] == Approx(big.params[i]).epsilon(1e-5));
            CHECK(tiny.stderr_[i] == Approx(big.stderr_[i]).epsilon(1e-4));
        }
    }
}

TEST_CASE(
    "fit: a constant the data do not determine at a tiny albedo fails the fit naming it, never a standard "
    "error of 0",
    "[checks][fit]") {
    // Hammon's multi weighs only the albedo^2 term: at albedo 1e-8 its standard error is large (~1e5), and at 1e-12
    // it changes no fitted value at all.
    const fit::DiffuseModel& m = fit::find_diffuse_model("hammon-2017");
    const std::vector<fit::DataPoint> pts = model_data(m, 7);
    const fit::LeastSquaresFit at_1e8 = fit::fit_model(m, {pts, {1e-8}, 0.02, {}}, "albedo 1e-8");
    for (std::size_t i = 0; i < m.parameters.size(); ++i) {
        INFO(m.parameters[i] << ": " << at_1e8.params[i] << " +- " << at_1e8.stderr_[i]);
        CHECK(at_1e8.stderr_[i] > 0.0);
        CHECK(std::isfinite(at_1e8.stderr_[i]));
    }
    CHECK(at_1e8.stderr_[4] > 1e3);  // multi: barely determined
    CHECK_THROWS_WITH(
        fit::fit_model(m, {pts, {1e-12}, 0.02, {}}, "albedo 1e-12"),
        Contains("hammon-2017") && Contains("albedo 1e-12") && Contains("does not determine its constant 'multi'"));
}

TEST_CASE("fit: an albedo below 1e-100 is refused at scene read with FILE:LINE", "[checks][fit][cli]") {
    using namespace smithlab_test;
    const fs::path d = scratch() / "tiny_albedos";
    fs::remove_all(d);
    fs::create_directories(d);
    for (const char* albedo : {"1e-101", "5e-324"}) {
        INFO(albedo);
        write(d / "s.toml",
              std::string("material = \"lambert(albedo=1)\"\nmodels = [\"lambert\"]\nalbedos = [0.5, ") + albedo +
                  "]\n[[ndf]]\nfamily = \"ggx\"\n");
        const Run r = run("fit '" + (d / "s.toml").string() + "' --output '" + (d / "out").string() + "'");
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Contains("s.toml:3") && Contains("albedos") && Contains("[1e-100, 1]"));
        CHECK_FALSE(fs::exists(d / "out"));
    }
    fs::remove_all(d);
}
