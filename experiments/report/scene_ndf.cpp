#include "scene_ndf.hpp"

#include <algorithm>

#include "smithlab/errors.hpp"
#include "smithlab/spec.hpp"

namespace smithlab::report {

std::vector<ParamPoint> NdfEntry::points() const {
    std::vector<ParamPoint> out{{}};
    for (const auto& [name, values] : axes) {
        std::vector<ParamPoint> next;
        for (const ParamPoint& p : out)
            for (double v : values) {
                next.push_back(p);
                next.back().emplace_back(name, v);
            }
        out = std::move(next);
    }
    return out;
}

std::size_t NdfEntry::count(std::size_t alphas) const {
    std::size_t n = roughness_given ? 1 : alphas;
    for (const auto& axis : axes) n *= axis.second.size();
    return n;
}

std::vector<std::string> ndf_table_keys(const NdfRegistry& registry, const std::vector<std::string>& extra) {
    std::vector<std::string> keys{"family"};
    for (const NdfInfo* info : registry.list())
        for (const std::string& p : info->parameters)
            if (std::find(keys.begin(), keys.end(), p) == keys.end()) keys.push_back(p);
    for (const std::string& e : extra)
        if (std::find(keys.begin(), keys.end(), e) == keys.end()) keys.push_back(e);
    return keys;
}

NdfEntry read_ndf_entry(StrictTable& t, const NdfRegistry& registry) {
    NdfEntry e{t.text("family"), {}, false, t.where("family")};
    const NdfInfo* info = registry.find(e.family);
    if (!info) {
        std::string known;
        for (const NdfInfo* i : registry.list()) known += (known.empty() ? "" : ", ") + i->name;
        t.fail("family", "names an unknown ndf family '" + e.family + "' (known: " + known + ")");
    }
    std::string own;
    for (const std::string& p : info->parameters) own += (own.empty() ? "" : ", ") + p;
    for (const NdfInfo* other : registry.list())
        for (const std::string& p : other->parameters)
            if (t.has(p) && std::find(info->parameters.begin(), info->parameters.end(), p) == info->parameters.end())
                t.fail(p, "is not a parameter of '" + e.family + "' (its parameters: " + own + ")");
    for (const std::string& p : info->parameters)
        if (t.has(p)) {
            e.axes.emplace_back(p, read_axis(t, p));
            if (p == "alpha" || (info->roughness && info->roughness->parameter == p)) e.roughness_given = true;
        }
    return e;
}

AnyNdf make_entry_ndf(const NdfEntry& e, const NdfRegistry& registry, const ParamPoint& point,
                      std::optional<double> alpha) {
    try {
        if (e.roughness_given || !alpha) return registry.make(e.family, point);
        return registry.make_at_alpha(e.family, *alpha, point);
    } catch (const input_error& err) {
        NdfSpec shown{e.family, point};
        if (alpha && !e.roughness_given) shown.params.insert(shown.params.begin(), {"alpha", *alpha});
        throw input_error(e.where + " '" + e.family + "' at " + format_spec(shown) + ": " + err.what());
    }
}

}  // namespace smithlab::report
