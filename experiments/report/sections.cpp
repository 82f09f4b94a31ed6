#include "report/sections.hpp"

namespace smithlab::report {

Sections builtin_sections() {
    Sections s;
    s.push_back(g1_section());
    s.push_back(g2_section());
    s.push_back(sampling_section());
    s.push_back(walk_section());
    s.push_back(figures_section());
    return s;
}

}  // namespace smithlab::report
