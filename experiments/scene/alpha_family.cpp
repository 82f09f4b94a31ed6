#include "scene/alpha_family.hpp"

#include "smithlab/spec.hpp"

namespace smithlab::scene {

std::string family_label(const AlphaFamily& f) {
    return f.params.empty() && f.entry.texts.empty() ? f.family() : format_spec({f.family(), f.params, f.entry.texts});
}

AnyNdf make_ndf(const NdfRegistry& registry, const AlphaFamily& f, double alpha) {
    return make_entry_ndf(f.entry, registry, f.params, alpha);
}

std::vector<AlphaFamily> read_alpha_families(StrictTable& doc, const NdfRegistry& registry, const std::string& sweep,
                                             const std::function<void(const StrictTable&, double)>& check) {
    std::vector<AlphaFamily> out;
    double families = 0.0;
    for (StrictTable& n : doc.tables("ndf", ndf_table_keys(registry))) {
        const NdfEntry e = read_ndf_entry(n, registry);
        if (!e.takes_alpha)
            n.fail("family",
                   "'" + e.family + "' has no parameter alpha and declares no roughness mapping to one: " + sweep);
        if (e.roughness_given) n.fail("family", "'" + e.family + "' is given its roughness here: " + sweep);
        double points = 1.0;
        for (const auto& axis : e.axes) points *= static_cast<double>(axis.second.size());
        families += points;
        if (check) check(n, families);
        for (const ParamPoint& p : e.points()) out.push_back({e, p});
        n.done();
    }
    if (out.empty()) doc.fail("ndf", "is missing: no [[ndf]] table names an NDF family");
    return out;
}

}  // namespace smithlab::scene
