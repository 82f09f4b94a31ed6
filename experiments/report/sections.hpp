// The report's built-in sections (section.hpp), one file each in report/sections/, and their list: a section is
// added by its file, its line below and its line in builtin_sections() (sections.cpp).
#pragma once

#include <memory>

#include "report/section.hpp"

namespace smithlab::report {

std::unique_ptr<Section> g1_section();  // [[ndf]], [variants]: every Lambda variant on the grid (g1_table.hpp)
std::unique_ptr<Section> g2_section();  // [g2]: the G2 approximations (g2_table.hpp)
std::unique_ptr<Section>
sampling_section();                       // [sampling]: the sampling-efficiency experiment (sampling_experiment.hpp)
std::unique_ptr<Section> walk_section();  // [walk]: albedo by scattering order, path-traced (walk_section.hpp)
std::unique_ptr<Section>
figures_section();  // [figures]: the Dimov 2015 reproductions and the figures' part of report.md

// All of the above, in that order: report.md's order.
Sections builtin_sections();

}  // namespace smithlab::report
