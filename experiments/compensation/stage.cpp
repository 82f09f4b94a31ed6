#include "compensation/stage.hpp"

#include "compensation/table_files.hpp"
#include "compensation/table_report.hpp"
#include "compensation/walk_furnace.hpp"
#include "output/plot_script.hpp"

namespace smithlab::compensation {

StageOutput run_compensation(const std::filesystem::path& dir, const std::vector<scene::AlphaFamily>& families,
                             const Settings& c, const NdfRegistry& registry, const StageRun& run) {
    if (!c.enabled) return {};
    StageOutput out{make_tables(families, c, registry, run), ""};
    const std::vector<FurnaceRow> rows = trace_furnace(out.tables, c, registry, run);
    write_table_files(dir, out.tables, c, registry, rows);
    const bool drawn = output::run_plot_script("compensation_plots.py", SMITHLAB_COMPENSATION_PLOT_SCRIPT, dir,
                                               run.command + ": compensation", {"furnace.png"});
    out.markdown = tables_markdown(out.tables, c, rows) +
        (drawn ? "\n![The furnace of the tables and against the walk](furnace.png)\n" : "");
    return out;
}

}  // namespace smithlab::compensation
