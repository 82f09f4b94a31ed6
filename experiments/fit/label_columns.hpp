// One column per parameter of the fitted NDFs beside the fit's ndf column ("gtr(gamma=1.5)": a column gamma holding
// 1.5), through output/ndf_columns.hpp: every parameter of each NDF but the roughness the fit sweeps over its alphas.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "fit/fit_data.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fit {

struct LabelColumns {
    std::vector<std::string> names;
    std::vector<std::vector<std::string>> cells;  // per NDF of the run, parallel to names
    std::vector<std::string> labels;              // the NDFs' labels, in the run's order

    // The columns but those a table has already (its own header).
    LabelColumns except(const std::vector<std::string>& header) const;
    // The header with the columns' names inserted at `at` (just after the ndf column).
    std::vector<std::string> header(std::vector<std::string> header, std::size_t at) const;
    // A row of NDF `label` with its cells inserted at `at`.
    std::vector<std::string> row(std::vector<std::string> row, std::size_t at, const std::string& label) const;
};

// The columns of the run's NDFs, each made at `alpha` (any alpha of the fit: the roughness is left out).
LabelColumns label_columns(const std::vector<NdfData>& data, const NdfRegistry& registry, double alpha);

}  // namespace smithlab::fit
