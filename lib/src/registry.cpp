#include "smithlab/registry.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <set>

#include "smithlab/errors.hpp"
#include "smithlab/ndfs.hpp"

namespace smithlab {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

bool is_identifier(std::string_view s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

[[noreturn]] void bad_spec(std::string_view text, const std::string& why) {
    throw input_error("ndf spec '" + std::string(text) + "': " + why);
}

}  // namespace

NdfSpec parse_spec(std::string_view text) {
    const std::string_view s = trim(text);
    NdfSpec spec;
    const auto open = s.find('(');
    spec.name = std::string(trim(s.substr(0, open)));
    if (!is_identifier(spec.name)) bad_spec(text, "expected a name like ggx(alpha=0.2)");
    if (open == std::string_view::npos) return spec;
    if (s.back() != ')') bad_spec(text, "missing closing ')'");
    std::string_view body = trim(s.substr(open + 1, s.size() - open - 2));
    if (body.empty()) return spec;
    std::set<std::string, std::less<>> seen;
    while (true) {
        const auto comma = body.find(',');
        const std::string_view item = trim(body.substr(0, comma));
        const auto eq = item.find('=');
        if (eq == std::string_view::npos) bad_spec(text, "parameter '" + std::string(item) + "' is not key=value");
        const std::string key(trim(item.substr(0, eq)));
        const std::string value(trim(item.substr(eq + 1)));
        if (!is_identifier(key)) bad_spec(text, "bad parameter name '" + key + "'");
        if (!seen.insert(key).second) bad_spec(text, "parameter '" + key + "' given twice");
        errno = 0;
        char* end = nullptr;
        const double v = value.empty() ? 0.0 : std::strtod(value.c_str(), &end);
        if (value.empty() || end != value.c_str() + value.size() || errno == ERANGE)
            bad_spec(text, "value of '" + key + "' is not a number: '" + value + "'");
        spec.params.emplace_back(key, v);
        if (comma == std::string_view::npos) break;
        body.remove_prefix(comma + 1);
    }
    return spec;
}

std::string format_spec(const std::string& name, const std::vector<std::pair<std::string, double>>& params) {
    std::string out = name + "(";
    for (std::size_t i = 0; i < params.size(); ++i) {
        char buf[64];
        const auto r = std::to_chars(buf, buf + sizeof buf, params[i].second);  // shortest round-trip form
        out += (i ? ", " : "") + params[i].first + "=" + std::string(buf, r.ptr);
    }
    return out + ")";
}

double NdfParams::at(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) throw input_error("ndf '" + ndf_ + "': missing parameter '" + key + "'");
    return it->second;
}

void NdfRegistry::add_erased(NdfInfo info, Factory make) {
    if (!is_identifier(info.name)) throw input_error("cannot register ndf with name '" + info.name + "'");
    if (find(info.name)) throw input_error("ndf '" + info.name + "' is already registered");
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

AnyNdf NdfRegistry::make(std::string_view text) const {
    const NdfSpec spec = parse_spec(text);
    const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const auto& e) { return e.first.name == spec.name; });
    if (it == entries_.end()) {
        std::string known;
        for (const auto& e : entries_) known += (known.empty() ? "" : ", ") + e.first.name;
        throw input_error("unknown ndf '" + spec.name + "' (known: " + known + ")");
    }
    const NdfInfo& info = it->first;
    std::map<std::string, double> values;
    std::vector<std::pair<std::string, double>> canonical;
    for (const auto& [key, v] : spec.params) {
        if (std::find(info.parameters.begin(), info.parameters.end(), key) == info.parameters.end())
            throw input_error("ndf '" + spec.name + "': unknown parameter '" + key + "'");
        values[key] = v;
    }
    for (const auto& key : info.parameters) {
        const auto v = values.find(key);
        if (v == values.end()) throw input_error("ndf '" + spec.name + "': missing parameter '" + key + "'");
        canonical.emplace_back(key, v->second);
    }
    return it->second(NdfParams(spec.name, std::move(values)), format_spec(spec.name, canonical));
}

void register_core_ndfs(NdfRegistry& r) {
    r.add({"ggx", {"alpha"}, "GGX / Trowbridge-Reitz (Walter 2007), closed-form Lambda",
           {"ggx(alpha=1e-4)", "ggx(alpha=0.01)", "ggx(alpha=0.3)", "ggx(alpha=1)"}},
          [](const NdfParams& p) { return ggx(p.at("alpha")); });
    r.add({"beckmann", {"alpha"}, "Beckmann (Walter 2007), closed-form Lambda",
           {"beckmann(alpha=1e-4)", "beckmann(alpha=0.05)", "beckmann(alpha=0.5)", "beckmann(alpha=1)"}},
          [](const NdfParams& p) { return beckmann(p.at("alpha")); });
    r.add({"blinn", {"n"}, "Blinn-Phong, D = (n+2)/(2 pi) cos^n; Lambda by quadrature",
           {"blinn(n=0.5)", "blinn(n=20)", "blinn(n=1000)"}},
          [](const NdfParams& p) { return blinn(p.at("n")); });
}

}  // namespace smithlab
