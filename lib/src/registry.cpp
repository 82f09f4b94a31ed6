#include "smithlab/registry.hpp"

#include <algorithm>
#include <cctype>

#include "smithlab/abc.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/ndfs.hpp"
#include "smithlab/student_t.hpp"
#include "smithlab/tabulated.hpp"

#include "smithlab/fit/diffuse_models.hpp"

namespace smithlab {

NdfRegistry::NdfRegistry() : diffuse_models_(fit::builtin_diffuse_registry()) {}

double NdfParams::at(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) throw input_error("ndf '" + ndf_ + "': missing parameter '" + key + "'");
    return it->second;
}

const std::string& NdfParams::text(const std::string& key) const {
    const auto it = texts_.find(key);
    if (it == texts_.end()) throw input_error("ndf '" + ndf_ + "': missing parameter '" + key + "'");
    return it->second;
}

void NdfRegistry::add_erased(NdfInfo info, Factory make) {
    if (!is_identifier(info.name)) throw input_error("cannot register ndf with name '" + info.name + "'");
    if (find(info.name)) throw input_error("ndf '" + info.name + "' is already registered");
    // What the registration declares of its parameters must name them: a slip here would surface as a user's error.
    auto declared = [&](const std::string& key) {
        return std::find(info.parameters.begin(), info.parameters.end(), key) != info.parameters.end();
    };
    for (const std::string& key : info.parameters)
        if (!is_identifier(key)) throw input_error("ndf '" + info.name + "': cannot register parameter '" + key + "'");
    for (const std::string& key : info.text_parameters)
        if (!is_identifier(key) || declared(key))
            throw input_error("ndf '" + info.name + "': cannot register text parameter '" + key + "'");
    if (info.roughness && !declared(info.roughness->parameter))
        throw input_error("ndf '" + info.name + "': its roughness sets '" + info.roughness->parameter +
                          "', which is not one of its parameters");
    for (const auto& [key, v] : info.defaults)
        if (!declared(key))
            throw input_error("ndf '" + info.name + "': a default for '" + key + "', not one of its parameters");
    entries_.emplace_back(std::move(info), std::move(make));
}

const NdfInfo* NdfRegistry::find(std::string_view name) const {
    for (const auto& [info, make] : entries_)
        if (info.name == name) return &info;
    return nullptr;
}

std::vector<const NdfInfo*> NdfRegistry::list() const {
    std::vector<const NdfInfo*> out;
    for (const auto& e : entries_) out.push_back(&e.first);
    return out;
}

namespace {
std::string parameter_list(const NdfInfo& info) {
    std::string out;
    for (const std::string& p : info.parameters) out += (out.empty() ? "" : ", ") + p;
    for (const std::string& p : info.text_parameters) out += (out.empty() ? "" : ", ") + p;
    return out.empty() ? "none" : out;
}
}  // namespace

std::vector<std::string> NdfRegistry::text_keys() const {
    std::vector<std::string> keys;
    for (const auto& [info, make] : entries_)
        for (const std::string& k : info.text_parameters)
            if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    return keys;
}

AnyNdf NdfRegistry::make_at_alpha(std::string_view family, double alpha,
                                  const std::vector<std::pair<std::string, double>>& others,
                                  const std::vector<std::pair<std::string, std::string>>& texts) const {
    const NdfInfo* info = find(family);
    if (!info) return make(family, others, texts);  // refused there, naming the known NDFs
    std::vector<std::pair<std::string, double>> params = others;
    if (std::find(info->parameters.begin(), info->parameters.end(), "alpha") != info->parameters.end()) {
        params.emplace_back("alpha", alpha);
    } else if (info->roughness) {
        std::map<std::string, double> given(others.begin(), others.end());
        for (const auto& [key, v] : info->defaults) given.emplace(key, v);  // what the spec may leave out
        params.emplace_back(
            info->roughness->parameter,
            info->roughness->from_alpha(alpha, NdfParams(info->name, std::move(given), {texts.begin(), texts.end()})));
    } else {
        throw input_error("ndf '" + info->name +
                          "' has no parameter 'alpha' and declares no roughness mapping to one " +
                          "(its parameters: " + parameter_list(*info) + "): it cannot be swept over alpha");
    }
    return make(family, params, texts);
}

AnyNdf NdfRegistry::make(std::string_view text) const {
    const NdfSpec spec = parse_spec(text, "ndf spec", text_keys());
    return make(spec.name, spec.params, spec.texts);
}

AnyNdf NdfRegistry::make(std::string_view family, const std::vector<std::pair<std::string, double>>& params,
                         const std::vector<std::pair<std::string, std::string>>& texts) const {
    const std::string name(family);
    if (!is_spec_name(name))  // as the parser says it of the spec these would spell
        throw input_error("ndf spec '" + format_spec({name, params}) + "': " + std::string(spec_name_rule));
    const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const auto& e) { return e.first.name == name; });
    if (it == entries_.end()) {
        std::string known;
        for (const auto& e : entries_) known += (known.empty() ? "" : ", ") + e.first.name;
        throw input_error("unknown ndf '" + name + "' (known: " + known + ")");
    }
    const NdfInfo& info = it->first;
    std::map<std::string, double> values;
    std::map<std::string, std::string> text_values;
    std::vector<std::pair<std::string, double>> canonical;
    std::vector<std::pair<std::string, std::string>> canonical_texts;
    for (const auto& [key, v] : texts) {
        if (std::find(info.text_parameters.begin(), info.text_parameters.end(), key) == info.text_parameters.end())
            throw input_error("ndf '" + name + "': unknown parameter '" + key +
                              "' (its parameters: " + parameter_list(info) + ")");
        if (!text_values.emplace(key, v).second)
            throw input_error("ndf '" + name + "': parameter '" + key + "' given twice");
    }
    for (const auto& key : info.text_parameters) {
        const auto v = text_values.find(key);
        if (v == text_values.end()) throw input_error("ndf '" + name + "': missing parameter '" + key + "'");
        canonical_texts.emplace_back(key, v->second);
    }
    for (const auto& [key, v] : params) {
        if (std::find(info.parameters.begin(), info.parameters.end(), key) == info.parameters.end())
            throw input_error("ndf '" + name + "': unknown parameter '" + key +
                              "' (its parameters: " + parameter_list(info) + ")");
        if (!values.emplace(key, v).second)
            throw input_error("ndf '" + name + "': parameter '" + key + "' given twice");
    }
    for (const auto& key : info.parameters) {
        const auto d =
            std::find_if(info.defaults.begin(), info.defaults.end(), [&](const auto& x) { return x.first == key; });
        auto v = values.find(key);
        if (v == values.end()) {
            if (d == info.defaults.end()) throw input_error("ndf '" + name + "': missing parameter '" + key + "'");
            v = values.emplace(key, d->second).first;
        }
        if (d == info.defaults.end() || !(v->second == d->second)) canonical.emplace_back(key, v->second);
    }
    return it->second(NdfParams(name, std::move(values), std::move(text_values)),
                      NdfSpec{name, std::move(canonical), std::move(canonical_texts)});
}

void register_core_ndfs(NdfRegistry& r) {
    r.add({"ggx",
           {"alpha"},
           "GGX / Trowbridge-Reitz (Walter 2007), closed-form Lambda",
           {"ggx(alpha=1e-4)", "ggx(alpha=0.01)", "ggx(alpha=0.3)", "ggx(alpha=1)"}},
          [](const NdfParams& p) { return ggx(p.at("alpha")); });
    r.add({"beckmann",
           {"alpha"},
           "Beckmann (Walter 2007), closed-form Lambda",
           {"beckmann(alpha=1e-4)", "beckmann(alpha=0.05)", "beckmann(alpha=0.5)", "beckmann(alpha=1)"}},
          [](const NdfParams& p) { return beckmann(p.at("alpha")); });
    // A roughness alpha sets n = 2 / alpha^2 - 2, the exponent at the Beckmann alpha it resembles (Walter et al.
    // 2007, sec. 5.2).
    r.add({"blinn",
           {"n"},
           "Blinn-Phong, D = (n+2)/(2 pi) cos^n; Lambda by quadrature",
           {"blinn(n=0.5)", "blinn(n=20)", "blinn(n=1000)"},
           NdfInfo::Roughness{"n", [](double alpha, const NdfParams&) { return 2.0 / (alpha * alpha) - 2.0; }}},
          [](const NdfParams& p) { return blinn(p.at("n")); });
    r.add({"student",
           {"alpha", "gamma"},
           "Student's t-distribution of slopes (Ribardiere et al. 2017), gamma in [1.65, 1e6]: GGX at 2, Beckmann as "
           "gamma -> inf; closed-form Lambda",
           {"student(alpha=1e-4, gamma=1.65)", "student(alpha=0.3, gamma=1.65)", "student(alpha=0.3, gamma=2)",
            "student(alpha=1, gamma=3)", "student(alpha=0.05, gamma=7.5)", "student(alpha=0.5, gamma=30)",
            "student(alpha=0.2, gamma=1e6)"}},
          [](const NdfParams& p) { return student(p.at("alpha"), p.at("gamma")); });
    // A measured NDF from a CSV table (tabulated.hpp), its slopes stretched by `scale`; a roughness alpha sets the
    // scale that makes its core slope scale (ndf.hpp) alpha: at alpha, a GGX or Beckmann table is that family's of
    // alpha.
    const auto read = [](const NdfParams& p) {
        const double normalize = p.at("normalize");
        require(normalize == 0.0 || normalize == 1.0, "tabulated: normalize", "0 or 1", normalize);
        return read_tabulated_ndf(p.text("file"), {.normalize = normalize == 1.0});
    };
    r.add({.name = "tabulated",
           .parameters = {"scale", "normalize"},
           .description = "a measured D(theta_m) from a CSV file (columns theta_deg or cos_theta, and D), interpolated "
                          "(tabulated.hpp); scale stretches its slopes (default 1), normalize=1 divides D by its "
                          "projected area; Lambda by quadrature",
           .examples = {},
           .roughness =
               NdfInfo::Roughness{
                   "scale", [read](double alpha, const NdfParams& p) { return alpha / core_slope_scale(read(p)); }},
           .text_parameters = {"file"},
           .defaults = {{"scale", 1.0}, {"normalize", 0.0}}},
          [read](const NdfParams& p) { return read(p).scaled(p.at("scale")); });
    register_abc(r);
}

}  // namespace smithlab
