// The figures as a report section (figures.hpp): the Dimov 2015 reproductions and the figures' part of report.md,
// as the scene's [figures] (read with the settings: the other sections draw by it too) names them.
#include "report/figures.hpp"
#include "report/sections.hpp"

namespace smithlab::report {

namespace {

class FiguresSection : public Section {
public:
    std::vector<std::string> keys() const override { return {}; }
    void read(scene::StrictTable&, const Settings&, const NdfRegistry&) override {}
    void add_work(Work&, const Settings&, const VariantRegistry&) const override {}
    void check(const Settings&, const NdfRegistry&, const VariantRegistry&) override {}
    void write(const std::filesystem::path& dir, const Settings& s) override { write_figures(s.figures, dir); }
    bool draws(const Settings& s) const override { return draws_figures(s.figures); }
};

}  // namespace

std::unique_ptr<Section> figures_section() { return std::make_unique<FiguresSection>(); }

}  // namespace smithlab::report
