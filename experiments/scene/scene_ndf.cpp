#include "scene/scene_ndf.hpp"

#include <algorithm>

#include "smithlab/errors.hpp"
#include "smithlab/spec.hpp"

namespace smithlab::scene {

namespace {
bool registry_declares(const NdfRegistry& registry, const std::string& key) {
    for (const NdfInfo* info : registry.list())
        if (std::find(info->parameters.begin(), info->parameters.end(), key) != info->parameters.end() ||
            std::find(info->text_parameters.begin(), info->text_parameters.end(), key) != info->text_parameters.end())
            return true;
    return false;
}
}  // namespace

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
    for (const NdfInfo* info : registry.list()) {
        for (const std::string& p : info->parameters)
            if (std::find(keys.begin(), keys.end(), p) == keys.end()) keys.push_back(p);
        for (const std::string& p : info->text_parameters)
            if (std::find(keys.begin(), keys.end(), p) == keys.end()) keys.push_back(p);
    }
    for (const std::string& e : extra)
        if (std::find(keys.begin(), keys.end(), e) == keys.end()) keys.push_back(e);
    return keys;
}

NdfEntry read_ndf_entry(StrictTable& t, const NdfRegistry& registry) {
    NdfEntry e{t.text("family"), {}, {}, false, true, t.where("family")};
    const NdfInfo* info = registry.find(e.family);
    if (!info) {
        std::string known;
        for (const NdfInfo* i : registry.list()) known += (known.empty() ? "" : ", ") + i->name;
        t.fail("family", "names an unknown ndf family '" + e.family + "' (known: " + known + ")");
    }
    std::vector<std::string> own = info->parameters;
    own.insert(own.end(), info->text_parameters.begin(), info->text_parameters.end());
    std::string listed;
    for (const std::string& p : own) listed += (listed.empty() ? "" : ", ") + p;
    for (const std::string& p : ndf_table_keys(registry))
        if (p != "family" && t.has(p) && std::find(own.begin(), own.end(), p) == own.end() &&
            registry_declares(registry, p))
            t.fail(p,
                   "is not a parameter of '" + e.family + "' (its parameters: " + (listed.empty() ? "none" : listed) +
                       ")");
    for (const std::string& p : info->text_parameters)
        if (t.has(p)) e.texts.emplace_back(p, t.text(p));
    for (const std::string& p : info->parameters)
        if (t.has(p)) {
            e.axes.emplace_back(p, read_axis(t, p));
            if (p == "alpha" || (info->roughness && info->roughness->parameter == p)) e.roughness_given = true;
        }
    e.takes_alpha = info->roughness || std::find(own.begin(), own.end(), "alpha") != own.end();
    if (!e.takes_alpha) e.roughness_given = true;
    return e;
}

AnyNdf make_entry_ndf(const NdfEntry& e, const NdfRegistry& registry, const ParamPoint& point,
                      std::optional<double> alpha) {
    try {
        if (e.roughness_given || !alpha) return registry.make(e.family, point, e.texts);
        return registry.make_at_alpha(e.family, *alpha, point, e.texts);
    } catch (const input_error& err) {
        NdfSpec shown{e.family, point, e.texts};
        if (alpha && !e.roughness_given) shown.params.insert(shown.params.begin(), {"alpha", *alpha});
        throw input_error(e.where + " '" + e.family + "' at " + format_spec(shown) + ": " + err.what());
    }
}

}  // namespace smithlab::scene
