#include "fit/label_columns.hpp"

#include <algorithm>

#include "output/ndf_columns.hpp"

namespace smithlab::fit {

namespace {

// The parameter an alpha sets in a family: alpha itself, or its registered roughness's parameter.
std::string roughness_parameter(const NdfRegistry& registry, const std::string& family) {
    const NdfInfo* info = registry.find(family);
    return info && info->roughness ? info->roughness->parameter : "alpha";
}

}  // namespace

LabelColumns label_columns(const std::vector<NdfData>& data, const NdfRegistry& registry, double alpha) {
    std::vector<AnyNdf> ndfs;
    std::vector<std::string> swept;
    LabelColumns out;
    for (const NdfData& d : data) {
        ndfs.push_back(make_ndf(registry, d.family, alpha));
        swept.push_back(roughness_parameter(registry, d.family.family()));
        out.labels.push_back(d.label);
    }
    const output::NdfColumns columns = output::ndf_columns(ndfs, swept);
    out.names = columns.names;
    for (const AnyNdf& n : ndfs) out.cells.push_back(columns.cells(n));
    return out;
}

LabelColumns LabelColumns::except(const std::vector<std::string>& header) const {
    LabelColumns out{{}, std::vector<std::vector<std::string>>(cells.size()), labels};
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (std::find(header.begin(), header.end(), names[i]) != header.end()) continue;
        out.names.push_back(names[i]);
        for (std::size_t n = 0; n < cells.size(); ++n) out.cells[n].push_back(cells[n][i]);
    }
    return out;
}

std::vector<std::string> LabelColumns::header(std::vector<std::string> h, std::size_t at) const {
    h.insert(h.begin() + static_cast<std::ptrdiff_t>(at), names.begin(), names.end());
    return h;
}

std::vector<std::string> LabelColumns::row(std::vector<std::string> r, std::size_t at, const std::string& label) const {
    const auto n = std::find(labels.begin(), labels.end(), label);
    const std::vector<std::string> none(names.size());
    const std::vector<std::string>& c = n == labels.end() ? none : cells[static_cast<std::size_t>(n - labels.begin())];
    r.insert(r.begin() + static_cast<std::ptrdiff_t>(at), c.begin(), c.end());
    return r;
}

}  // namespace smithlab::fit
