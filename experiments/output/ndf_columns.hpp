// One column per NDF parameter beside the spec string, so that a table of several NDFs reads without parsing specs
// (pandas: df[df.gamma == 1.5]). The columns are the union of the NDFs' parameters, each family's in its declared
// order, a family's first appearance first; a row's cell is empty where its NDF has no such parameter.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "smithlab/any_ndf.hpp"

namespace smithlab::output {

struct NdfColumns {
    // The column names: every parameter (numbers, then texts such as a table's file) of the NDFs but those in the
    // table's own columns already (a roughness column "alpha", say).
    std::vector<std::string> names;
    // The cells of one NDF's row, parallel to names: the shortest round-trip text of each number, the text as given.
    std::vector<std::string> cells(const AnyNdf& ndf) const;
};

NdfColumns ndf_columns(std::span<const AnyNdf> ndfs, const std::vector<std::string>& taken = {});

}  // namespace smithlab::output
