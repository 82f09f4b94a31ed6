// The sampling-efficiency experiment as a report section (sampling_experiment.hpp): the scene's [sampling]
// (families, alpha, theta_o, samples, seed). Without it, nothing (its work still shows as samples 0).
#include <cstdint>
#include <cstdio>

#include "report/sampling_experiment.hpp"
#include "report/sections.hpp"
#include "scene/limits.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace {

class SamplingSection : public Section {
public:
    std::vector<std::string> keys() const override { return {"sampling"}; }

    void read(scene::StrictTable& doc, const Settings& settings, const NdfRegistry& registry) override {
        auto sm = doc.optional_table("sampling", {"families", "alpha", "theta_o", "samples", "seed"});
        if (!sm) return;
        scene_.families = sm->texts("families");
        if (scene_.families.empty()) sm->fail("families", "is an empty list");
        scene_.alphas = scene::read_axis(*sm, "alpha");
        scene_.theta_o = sm->real("theta_o", scene_.theta_o);
        if (!(scene_.theta_o >= 0.0 && scene_.theta_o < 90.0))
            sm->fail("theta_o", "must be in [0, 90) degrees, got " + format_shortest(scene_.theta_o));
        scene_.samples = static_cast<std::size_t>(
            scene::scaled_count(sm->integer("samples", 100, 100'000'000, 100'000), settings.scale, 100));
        scene_.seed = static_cast<unsigned long long>(sm->integer("seed", 0, INT64_MAX, 1));
        sm->done();
        try {
            ndfs_ = sampling_ndfs(scene_, registry);
        } catch (const input_error& e) {
            sm->fail("families", e.what());
        }
    }

    // samples: families x alpha x strategies x samples.
    void add_work(Work& work, const Settings&, const VariantRegistry&) const override {
        work.add("samples",
                 static_cast<double>(scene_.families.size() * scene_.alphas.size() * sampling_strategies.size()) *
                     static_cast<double>(scene_.samples));
    }

    void check(const Settings&, const NdfRegistry&, const VariantRegistry&) override {}  // all checked as read

    void compute() override {
        if (ndfs_.empty()) return;
        std::fprintf(stderr, "report: sampling experiment, %zu x %zu estimates of %zu samples\n", ndfs_.size(),
                     sampling_strategies.size(), scene_.samples);
        rows_ = run_sampling_experiment(ndfs_, scene_);
    }

    void add_timing(Timing& timing) override { add_sampling_timing(rows_, scene_, timing); }

    void write(const std::filesystem::path& dir, const Settings&) override {
        if (!rows_.empty()) write_sampling_section(rows_, scene_, dir);
    }

    bool draws(const Settings&) const override { return !scene_.families.empty(); }

private:
    SamplingScene scene_;
    std::vector<AnyNdf> ndfs_;
    std::vector<SamplingRow> rows_;
};

}  // namespace

std::unique_ptr<Section> sampling_section() { return std::make_unique<SamplingSection>(); }

}  // namespace smithlab::report
