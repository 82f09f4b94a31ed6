// The facet materials' values: a material's declaration as a spec, its parameters, and the dispatch of Material.
#include "smithlab/walk/material.hpp"

#include <cmath>
#include <stdexcept>

#include "smithlab/csv.hpp"
#include "smithlab/surface.hpp"
#include "smithlab/walk/material_info.hpp"

namespace smithlab::walk {

std::string MaterialInfo::spec() const {
    std::string s = name;
    for (std::size_t i = 0; i < parameters.size(); ++i) {
        const MaterialParameter& p = parameters[i];
        s += (i == 0 ? "(" : ", ") + p.key + "=" + (std::isnan(p.fallback) ? "" : format_printf("%g", p.fallback));
    }
    return parameters.empty() ? s : s + ")";
}

double MaterialParams::at(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) throw std::out_of_range("material '" + name_ + "': no parameter '" + key + "'");
    return it->second;
}

bool Material::dirac_at(const Vec3& wi, const Vec3& wo) const {
    return visit(
        *this, [&](const auto& m) { return material_dirac_at(m, wi, wo); },
        [&](const MaterialKernels& kernels) { return kernels.dirac_at(wi, wo); });
}

}  // namespace smithlab::walk
