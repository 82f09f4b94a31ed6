// smithlab tables: the energy-compensation stage (experiments/compensation/) from the command line, without a fit.
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "compensation/tables_run.hpp"
#include "compensation/tables_scene.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::cli {

void add_tables(CLI::App& app, TablesArgs& a) {
    CLI::App* c =
        app.add_subcommand("tables", "Tabulate the energy compensation of specular multiple scattering for renderers");
    c->footer(
        "Tabulates, for every NDF family of the scene and each G2 form (height-correlated, separable), the "
        "directional\n"
        "albedo E(mu) of single scattering off mirror facets and 1 - E_avg that Kulla and Conty's (2017) and "
        "Turquin's\n"
        "(2019) compensation need, with eta a dielectric's E_R + E_T from both sides, by quadrature on a cosine axis\n"
        "warped by each NDF's masking scale; measures each table against the exact values on a grid refine x finer "
        "and\n"
        "in the white furnace, by its own lookups and against the random walk; with order_walks, tables of the walk's\n"
        "scattering orders for conductors. The scene's [compensation] is a fit scene's: `smithlab fit` writes the "
        "same\n"
        "files, the same bytes for the same [[ndf]], [compensation] and seed, beside its fit. With no scene it runs "
        "the\n"
        "embedded default (GGX; --print-scene shows it and documents every key).\n"
        "Examples:\n"
        "  smithlab tables\n"
        "  smithlab tables --print-scene > gtr.toml   # edit: [[ndf]] family = \"gtr\", gamma = [1, 1.5, 3]\n"
        "  smithlab tables gtr.toml -o gtr-tables/ --threads 8\n"
        "Writes into DIR (-o, default tables/): compensation/ (for renderers, per table ID.h (C99), ID.glsl, ID.hlsl,\n"
        "ID.png (16-bit grey) and ID.json (its axes); with order_walks, per family and G2 ID_orders.h, .glsl, .hlsl "
        "and\n"
        ".json; docs/compensation.md); compensation.csv, compensation_avg.csv and compensation_dielectric.csv (the\n"
        "tables at their nodes), compensation_orders.csv (the scattering orders), compensation_error.csv (each "
        "table's\n"
        "measured errors), furnace_tables.csv, furnace.csv and furnace.png (the furnace, by the tables and against "
        "the\n"
        "walk); report.md; meta.json; all only when complete. Progress goes to stderr.");
    add_scene_options(*c, a.scene, a.print_scene, a.limits.scale, "the embedded default");
    add_output_option(*c, a.output, "output directory")->capture_default_str();
    add_threads_option(*c, a.threads);
    add_max_walks_option(*c, a.limits);
}

int run_tables(const TablesArgs& a, const NdfRegistry& registry) {
    if (a.print_scene) {
        std::cout << compensation::default_tables_scene_text();
        return exit_ok;
    }
    require_threads(a.threads);
    require_scale(a.limits.scale);
    const std::string source = a.scene.empty() ? "<default scene>" : a.scene;
    const std::string text = a.scene.empty() ? compensation::default_tables_scene_text() : read_scene_file(a.scene);
    const compensation::TablesScene scene = compensation::parse_tables_scene(text, source, registry, a.limits);
    const compensation::TablesSummary sum =
        compensation::run_tables(scene, source, text, registry, a.output, static_cast<unsigned>(a.threads));
    std::printf("%-16s %-18s %-28s %12s %13s\n", "ndf", "g2", "table", "interp_error", "furnace_error");
    for (const compensation::TablesSummary::Row& r : sum.rows)
        std::printf("%-16s %-18s %-28s %12.2e %13.2e\n", r.ndf.c_str(), r.g2.c_str(), r.table.c_str(), r.interpolation,
                    r.furnace);
    std::printf("seconds %.3g\noutput %s\n", sum.seconds, a.output.c_str());
    return exit_ok;
}

}  // namespace smithlab::cli
