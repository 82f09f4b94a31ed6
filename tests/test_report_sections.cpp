// A report section of one's own (experiments/report/section.hpp): the worked example of docs/extending.md. The
// section below reads its table of the scene, counts its work, checks its input, computes, and writes a CSV file
// and its part of report.md; added to the built-in list, it runs in a report like the others, after them.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "report/report.hpp"
#include "report/scene.hpp"
#include "report/section.hpp"
#include "report/sections.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr.hpp"

namespace fs = std::filesystem;
using namespace smithlab;

namespace {

// [docs: report-section]
// [ggx_g1] alpha = AXIS, mu = REAL: G1 = 1 / (1 + Lambda) of GGX at mu for each alpha, from the NDF's Lambda.
class GgxG1Section : public report::Section {
public:
    explicit GgxG1Section(std::shared_ptr<int> computed) : computed_(std::move(computed)) {}

    std::vector<std::string> keys() const override { return {"ggx_g1"}; }

    void read(scene::StrictTable& doc, const report::Settings&, const NdfRegistry&) override {
        auto t = doc.optional_table("ggx_g1", {"alpha", "mu"});
        if (!t) return;
        alphas_ = scene::read_axis(*t, "alpha");
        mu_ = t->real("mu", mu_);
        if (!(mu_ > 0.0 && std::isfinite(mu_))) t->fail("mu", "must be finite and > 0");
        t->done();
    }

    void add_work(report::Work& work, const report::Settings&, const VariantRegistry&) const override {
        work.add("G1 of GGX", static_cast<double>(alphas_.size()), false);
    }

    void check(const report::Settings&, const NdfRegistry& ndfs, const VariantRegistry&) override {
        for (double a : alphas_) ndfs_.push_back(ndfs.make("ggx", {{"alpha", a}}));  // the registry checks alpha
    }

    void compute() override {
        for (const AnyNdf& n : ndfs_) G1_.push_back(1.0 / (1.0 + n.Lambda(mu_)));
        ++*computed_;
    }

    void write(const fs::path& dir, const report::Settings&) override {
        if (ndfs_.empty()) return;
        std::ofstream csv(dir / "ggx_g1.csv");
        write_csv_record(csv, {"alpha", "mu", "G1"});
        for (std::size_t i = 0; i < ndfs_.size(); ++i)
            write_csv_record(csv, {format_g17(alphas_[i]), format_g17(mu_), format_g17(G1_[i])});
        std::ofstream(dir / "report.md", std::ios::app) << "\n## G1 of GGX at mu = " << mu_ << "\n\nSee ggx_g1.csv.\n";
    }

private:
    std::vector<double> alphas_;
    double mu_ = 1.0;
    std::vector<AnyNdf> ndfs_;
    std::vector<double> G1_;
    std::shared_ptr<int> computed_;
};
// [end docs]

// [docs: report-section-list]
// The built-in sections and the example after them.
report::Sections with_example(std::shared_ptr<int> computed) {
    report::Sections sections = report::builtin_sections();
    sections.push_back(std::make_unique<GgxG1Section>(std::move(computed)));
    return sections;
}
// [end docs]

const std::string quick_scene =
    "[grid]\n"                       // 1
    "alpha = [0.1, 0.5]\n"           // 2
    "mu = [1.0, 2.0]\n"              // 3
    "[[ndf]]\n"                      // 4
    "family = \"ggx\"\n"             // 5
    "[variants]\n"                   // 6
    "include = [\"schlick-ggx\"]\n"  // 7
    "[timing]\n"                     // 8
    "min_time = 0.001\n";            // 9

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

fs::path fresh_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("smithlab_report_sections_" + std::to_string(::getpid())) / name;
    fs::remove_all(d);
    fs::create_directories(d.parent_path());
    return d;
}

}  // namespace

TEST_CASE("report sections: a section of one's own runs in a report, after the built-in ones", "[report]") {
    const NdfRegistry ndfs = builtin_registry();
    const VariantRegistry variants = builtin_variants();
    auto computed = std::make_shared<int>(0);
    report::Scene scene = report::parse_scene(quick_scene + "[ggx_g1]\nalpha = [0.1, 0.5, 1.0]\nmu = 0.5\n",
                                              "example.toml", ndfs, with_example(computed));
    CHECK_THAT(report::describe(report::estimate_work(scene, variants)), Catch::Contains(", G1 of GGX 3)"));

    const fs::path out = fresh_dir("example");
    REQUIRE(report::run_report(scene, out.string(), ndfs, variants) == 0);
    CHECK(*computed == 1);
    // Its values: GGX's G1 in closed form (Walter et al. 2007, eq. 34), 2 / (1 + sqrt(1 + alpha^2 / mu^2)).
    std::ifstream csv(out / "ggx_g1.csv");
    const auto records = read_csv(csv);
    REQUIRE(records.size() == 4);
    for (std::size_t i = 1; i < records.size(); ++i) {
        const double alpha = std::stod(records[i].fields[0]), mu = std::stod(records[i].fields[1]);
        CHECK(std::stod(records[i].fields[2]) ==
              Approx(2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha / (mu * mu)))).epsilon(1e-13));
    }
    // Its part of report.md comes after the built-in sections' (the G1 table's here).
    const std::string md = slurp(out / "report.md");
    const auto table = md.find("| schlick-ggx |"), own = md.find("## G1 of GGX at mu = 0.5");
    REQUIRE(table != std::string::npos);
    REQUIRE(own != std::string::npos);
    CHECK(table < own);
}

TEST_CASE("report sections: a section's keys are read strictly, and only where it is in the list", "[report]") {
    const NdfRegistry ndfs = builtin_registry();
    auto computed = std::make_shared<int>(0);
    const std::string misspelt = quick_scene + "[ggx_g1]\nalpah = [0.1]\n";  // lines 10, 11
    CHECK_THROWS_WITH(report::parse_scene(misspelt, "example.toml", ndfs, with_example(computed)),
                      Catch::Contains("example.toml:11:") && Catch::Contains("did you mean 'ggx_g1.alpha'?"));
    const std::string own = quick_scene + "[ggx_g1]\nalpha = [0.1]\n";
    CHECK_THROWS_WITH(report::parse_scene(own, "example.toml", ndfs),
                      Catch::Contains("example.toml:10:") && Catch::Contains("unknown section 'ggx_g1'"));
    // Without its table it does nothing: no work, no file.
    report::Scene scene = report::parse_scene(quick_scene, "example.toml", ndfs, with_example(computed));
    CHECK_THAT(report::describe(report::estimate_work(scene, builtin_variants())), !Catch::Contains("G1 of GGX"));
}

TEST_CASE("report sections: every section checks its input before any computes", "[report]") {
    const NdfRegistry ndfs = builtin_registry();
    const VariantRegistry variants = builtin_variants();
    auto computed = std::make_shared<int>(0);
    // The example section's alpha is refused by the GGX parser; the sampling experiment (before it) computes nothing.
    report::Scene scene = report::parse_scene(quick_scene +
                                                  "[sampling]\nfamilies = [\"ggx\"]\nalpha = [0.1]\nsamples = 1000\n"
                                                  "[ggx_g1]\nalpha = [-1.0]\n",
                                              "example.toml", ndfs, with_example(computed));
    const fs::path out = fresh_dir("refused");
    CHECK_THROWS_AS(report::run_report(scene, out.string(), ndfs, variants), input_error);
    CHECK(*computed == 0);
    CHECK_FALSE(fs::exists(out));
}
