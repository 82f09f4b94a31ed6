// The files of the energy-compensation stage (compensation/stage.hpp), into an output directory:
//   compensation.csv, compensation_avg.csv, compensation_dielectric.csv (with eta): the tables at their nodes;
//   compensation_orders.csv (with order_walks): the walk's scattering orders at theirs;
//   compensation_error.csv: each table's worst interpolation error, below-grid error and furnace error, and where;
//   furnace_tables.csv: the furnace by the tables per alpha of the check grid; furnace.csv: against the walk
//   (compensation/walk_furnace.hpp);
//   compensation/ (smithlab/compensation/compensation_formats.hpp): a C header, GLSL, HLSL, a 16-bit PNG and its axes
//   per table; a C header, GLSL, HLSL and JSON of the scattering orders per family and G2 form.
#pragma once

#include <filesystem>
#include <vector>

#include "compensation/settings.hpp"
#include "compensation/tables.hpp"
#include "compensation/walk_furnace.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::compensation {

void write_table_files(const std::filesystem::path& dir, const std::vector<FamilyTables>& all, const Settings& c,
                       const NdfRegistry& registry, const std::vector<FurnaceRow>& furnace);

}  // namespace smithlab::compensation
