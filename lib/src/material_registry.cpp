#include "smithlab/material_registry.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/spec.hpp"

namespace smithlab {

namespace {

// The spec's parameters by key, each checked against the material's declaration: unknown keys refused, required
// ones demanded, defaults filled in, every value in its range.
walk::MaterialParams checked_params(const walk::MaterialInfo& info, const NdfSpec& spec) {
    std::map<std::string, double> given;
    for (const auto& [key, value] : spec.params) {
        const auto declared = std::find_if(info.parameters.begin(), info.parameters.end(),
                                           [&](const walk::MaterialParameter& p) { return p.key == key; });
        if (declared == info.parameters.end()) {
            std::string known;
            for (const walk::MaterialParameter& p : info.parameters) known += (known.empty() ? "" : ", ") + p.key;
            throw input_error("material '" + info.name + "': unknown parameter '" + key + "'" +
                              (known.empty() ? " (it takes none)" : " (it takes " + known + ")"));
        }
        given[key] = value;
    }
    std::map<std::string, double> values;
    for (const walk::MaterialParameter& p : info.parameters) {
        const auto it = given.find(p.key);
        if (it == given.end()) {
            if (std::isnan(p.fallback))
                throw input_error("material '" + info.name + "': parameter '" + p.key + "' is required");
            values[p.key] = p.fallback;
            continue;
        }
        require(it->second >= p.lo && it->second <= p.hi, "material '" + info.name + "': " + p.key,
                "in [" + format_printf("%g", p.lo) + ", " + format_printf("%g", p.hi) + "]", it->second);
        values[p.key] = it->second;
    }
    return {info.name, std::move(values)};
}

}  // namespace

MaterialRegistry::MaterialRegistry() {
    add<walk::Mirror>();
    add<walk::Conductor>();
    add<walk::Lambert>();
    add<walk::FresnelDiffuse>();
    add<walk::Dielectric>();
}

void MaterialRegistry::add_erased(walk::MaterialInfo info, Factory make) {
    if (!is_spec_name(info.name))
        throw input_error("material name '" + info.name + "': " + std::string(spec_name_rule));
    if (find(info.name)) throw input_error("material '" + info.name + "' is registered twice");
    entries_.emplace_back(std::move(info), std::move(make));
}

walk::Material MaterialRegistry::make(std::string_view text) const {
    const NdfSpec spec = parse_spec(text, "material spec");
    for (const auto& [info, factory] : entries_)
        if (info.name == spec.name) return factory(checked_params(info, spec));
    std::string known;
    for (const auto& [info, factory] : entries_) known += (known.empty() ? "" : ", ") + info.spec();
    throw input_error("unknown material '" + spec.name + "' (known: " + known + ")");
}

const walk::MaterialInfo* MaterialRegistry::find(std::string_view name) const {
    for (const auto& [info, factory] : entries_)
        if (info.name == name) return &info;
    return nullptr;
}

std::vector<const walk::MaterialInfo*> MaterialRegistry::list() const {
    std::vector<const walk::MaterialInfo*> out;
    for (const auto& [info, factory] : entries_) out.push_back(&info);
    return out;
}

}  // namespace smithlab
