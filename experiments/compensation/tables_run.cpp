#include "compensation/tables_run.hpp"

#include <chrono>
#include <nlohmann/json.hpp>

#include "compensation/stage.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/compensation/furnace.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::compensation {

namespace fs = std::filesystem;

namespace {

void write_meta(const fs::path& dir, const TablesScene& s, const std::string& source, const std::string& scene_text,
                double seconds, unsigned threads) {
    const nlohmann::ordered_json meta = {{"title", s.title},
                                         {"source", source},
                                         {"scene", scene_text},
                                         {"version", SMITHLAB_VERSION},
                                         {"seed", s.seed},
                                         {"seconds", seconds},
                                         {"threads", util::thread_count(threads)}};
    output::write_file(dir / "meta.json", meta.dump(2) + "\n");
}

std::vector<TablesSummary::Row> summary_rows(const std::vector<FamilyTables>& all) {
    std::vector<TablesSummary::Row> rows;
    for (const FamilyTables& t : all)
        for_each_table(t, [&](const MeasuredTable& m) {
            rows.push_back({family_label(*t.family), g2_name(t.g2), m.name, m.table.error.max,
                            compensation::worst_of(m.furnace).max});
        });
    return rows;
}

}  // namespace

TablesSummary run_tables(const TablesScene& s, const std::string& source, const std::string& scene_text,
                         const NdfRegistry& registry, const fs::path& out, unsigned threads) {
    const auto t0 = std::chrono::steady_clock::now();
    output::StagedDirectory stage(out, "tables");  // refuses a bad OUT before any work
    const StageOutput tables =
        run_compensation(stage.path(), s.ndfs, s.compensation, registry, {"tables", s.seed, threads});
    output::write_file(stage.path() / "report.md", "# " + s.title + "\n" + tables.markdown);
    TablesSummary sum{summary_rows(tables.tables),
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
    write_meta(stage.path(), s, source, scene_text, sum.seconds, threads);
    stage.publish();
    return sum;
}

}  // namespace smithlab::compensation
