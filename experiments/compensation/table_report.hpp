// The energy-compensation stage's section of a report.md (fit's, tables'): the tables' grid, each table's measured
// errors, the walk's scattering orders and their standard error, and the furnace against the walk, worst per material,
// part and form.
#pragma once

#include <string>
#include <vector>

#include "compensation/settings.hpp"
#include "compensation/tables.hpp"
#include "compensation/walk_furnace.hpp"

namespace smithlab::compensation {

// The section in Markdown, opening "\n## Energy compensation ...".
std::string tables_markdown(const std::vector<FamilyTables>& all, const Settings& c,
                            const std::vector<FurnaceRow>& furnace);

}  // namespace smithlab::compensation
