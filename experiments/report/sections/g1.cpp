// The G1 table as a report section (g1_table.hpp): the scene's [[ndf]] (the grid's NDFs, each over [grid] alpha
// unless it gives its own roughness) and [variants] (include, exclude: glob patterns over variant names).
#include <algorithm>

#include "report/g1_table.hpp"
#include "report/scene.hpp"
#include "report/sections.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace {

bool matches_any(const std::vector<std::string>& patterns, const std::string& name) {
    return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return glob_match(p, name); });
}

class G1Section : public Section {
public:
    std::vector<std::string> keys() const override { return {"ndf", "variants"}; }

    void read(scene::StrictTable& doc, const Settings&, const NdfRegistry& registry) override {
        for (scene::StrictTable& n : doc.tables("ndf", scene::ndf_table_keys(registry))) {
            entries_.push_back(scene::read_ndf_entry(n, registry));
            n.done();
        }
        if (entries_.empty()) doc.fail("ndf", "is missing: no [[ndf]] table names an NDF family");
        scene::StrictTable variants = doc.table("variants", {"include", "exclude"});
        include_ = variants.texts("include");
        exclude_ = variants.texts("exclude", {});
        where_include_ = variants.where("include");
        where_exclude_ = variants.where("exclude");
        variants.done();
    }

    // Lambda: the selected variants (the family evaluator twice: one call and the stream) x the grid's NDFs x mu, each
    // counted on every NDF; references: per point one per route, at most 3.
    void add_work(Work& work, const Settings& s, const VariantRegistry& variants) const override {
        double selected = 0.0, ndfs = 0.0;
        for (const LambdaVariant& v : variants.list())
            if (selects(v.name)) selected += v.name == "family" ? 2.0 : 1.0;
        for (const scene::NdfEntry& e : entries_) ndfs += static_cast<double>(e.count(s.alphas.size()));
        const double points = ndfs * static_cast<double>(s.mus.size());
        work.add("Lambda", selected * points);
        work.add("references", std::min(selected, 3.0) * points);
    }

    void check(const Settings& s, const NdfRegistry& ndfs, const VariantRegistry& variants) override {
        std::vector<std::string> names;
        for (const LambdaVariant& v : variants.list()) names.push_back(v.name);
        // A pattern that matches nothing, and a selection of nothing, named with the key's FILE:LINE.
        require_matches(include_, names, where_include_);
        require_matches(exclude_, names, where_exclude_);
        if (std::none_of(names.begin(), names.end(), [&](const std::string& n) { return selects(n); }))
            throw input_error(where_exclude_ +
                              " leaves no variant of the ones include selects (see smithlab eval "
                              "--list-methods)");
        table_ = g1_table(entries_, s.alphas, ndfs, variants, include_, exclude_);
        require_g1_domain(table_, s.mus);
        mus_ = s.mus;
        keep_errors_ = draws(s);
    }

    void measure(ReferenceCache& cache) override { measure_g1(table_, mus_, cache, keep_errors_); }
    void add_timing(Timing& timing) override { add_g1_timing(table_, mus_, timing); }

    void write(const std::filesystem::path& dir, const Settings& s) override {
        write_g1_table(table_, s.alphas, s.mus, dir);
        if (keep_errors_) write_g1_points(table_, dir);
    }

    bool draws(const Settings& s) const override { return s.figures.pareto || s.figures.error_maps; }

private:
    // Whether [variants] selects the variant: include matches it and exclude does not (as g1_table selects).
    bool selects(const std::string& name) const { return matches_any(include_, name) && !matches_any(exclude_, name); }

    std::vector<scene::NdfEntry> entries_;
    std::vector<std::string> include_, exclude_;
    std::string where_include_, where_exclude_;  // for a pattern that matches no variant
    G1Table table_;
    std::vector<double> mus_;
    bool keep_errors_ = false;  // the figures pareto and error_maps draw every point
};

}  // namespace

std::unique_ptr<Section> g1_section() { return std::make_unique<G1Section>(); }

}  // namespace smithlab::report
