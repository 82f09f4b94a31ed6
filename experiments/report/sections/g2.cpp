// The G2 table as a report section (g2_table.hpp): the scene's [g2] (include: glob patterns over the G2 variants;
// families; mu), over [grid] alpha. Without [g2], nothing (its work still shows as G2 0).
#include <algorithm>

#include "report/g2_table.hpp"
#include "report/scene.hpp"
#include "report/sections.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace {

class G2Section : public Section {
public:
    std::vector<std::string> keys() const override { return {"g2"}; }

    void read(scene::StrictTable& doc, const Settings&, const NdfRegistry& registry) override {
        auto g2 = doc.optional_table("g2", {"include", "families", "mu"});
        if (!g2) return;
        include_ = g2->texts("include");
        std::vector<std::string> names;
        for (const G2Variant& v : builtin_G2_variants()) names.push_back(v.name);
        require_matches(include_, names, g2->where("include"));
        families_ = g2->texts("families", families_);
        for (const std::string& f : families_) try {
                registry.make(f, {{"alpha", 0.5}});  // a family of roughness alpha (each alpha is grid.alpha's)
            } catch (const input_error& e) {
                g2->fail("families", e.what());
            }
        mus_ = scene::read_axis(*g2, "mu");
        require_positive_mus(*g2, "mu", mus_);
        g2->done();
    }

    // G2: the selected G2 variants x families x alpha x mu_i x mu_o; references: families x alpha x mu.
    void add_work(Work& work, const Settings& s, const VariantRegistry&) const override {
        double selected = 0.0;
        if (!include_.empty())
            for (const G2Variant& v : builtin_G2_variants())
                if (std::any_of(include_.begin(), include_.end(),
                                [&](const std::string& p) { return glob_match(p, v.name); }))
                    selected += 1.0;
        const double ndfs = static_cast<double>(families_.size() * s.alphas.size()),
                     mus = static_cast<double>(mus_.size());
        work.add("G2", selected * ndfs * mus * mus);
        if (selected > 0.0) work.add("references", ndfs * mus);
    }

    void check(const Settings& s, const NdfRegistry& ndfs, const VariantRegistry&) override {
        table_ = g2_table(include_, families_, s.alphas, mus_, ndfs);
    }

    void measure(ReferenceCache& cache) override { measure_g2(table_, mus_, cache); }
    void add_timing(Timing& timing) override { add_g2_timing(table_, timing); }
    void write(const std::filesystem::path& dir, const Settings&) override { write_g2_table(table_, dir); }

private:
    std::vector<std::string> include_;  // empty: no G2 table
    std::vector<std::string> families_ = {"ggx"};
    std::vector<double> mus_;
    G2Table table_;
};

}  // namespace

std::unique_ptr<Section> g2_section() { return std::make_unique<G2Section>(); }

}  // namespace smithlab::report
