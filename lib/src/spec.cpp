#include "smithlab/spec.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

}  // namespace

bool is_identifier(std::string_view s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    return std::all_of(s.begin(), s.end(),
                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

namespace {

[[noreturn]] void bad_spec(std::string_view what, std::string_view text, const std::string& why) {
    throw input_error(std::string(what) + " '" + std::string(text) + "': " + why);
}

}  // namespace

bool is_spec_name(std::string_view s) {
    return !s.empty() && s[0] != '-' && s.back() != '-' && is_identifier(s.substr(0, 1)) &&
        std::all_of(s.begin(), s.end(),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
}

namespace {

// A bare text value holds no blank, comma, parenthesis or double quote (it must read back as one item).
bool is_bare_text(std::string_view v) {
    return !v.empty() && std::none_of(v.begin(), v.end(), [](char c) {
        return std::isspace(static_cast<unsigned char>(c)) || c == ',' || c == '(' || c == ')' || c == '"';
    });
}

}  // namespace

NdfSpec parse_spec(std::string_view text, std::string_view what, const std::vector<std::string>& text_keys) {
    const std::string_view s = trim(text);
    NdfSpec spec;
    const auto open = s.find('(');
    spec.name = std::string(trim(s.substr(0, open)));
    if (!is_spec_name(spec.name)) bad_spec(what, text, std::string(spec_name_rule));
    if (open == std::string_view::npos) return spec;
    if (s.back() != ')') bad_spec(what, text, "missing closing ')'");
    std::string_view body = trim(s.substr(open + 1, s.size() - open - 2));
    if (body.empty()) return spec;
    std::set<std::string, std::less<>> seen;
    while (true) {
        // The item ends at the first comma outside double quotes.
        std::size_t end = 0;
        for (bool quoted = false; end < body.size() && (quoted || body[end] != ','); ++end)
            if (body[end] == '"') quoted = !quoted;
        const std::string_view item = trim(body.substr(0, end));
        const auto eq = item.find('=');
        if (eq == std::string_view::npos)
            bad_spec(what, text, "parameter '" + std::string(item) + "' is not key=value");
        const std::string key(trim(item.substr(0, eq)));
        const std::string value(trim(item.substr(eq + 1)));
        if (!is_identifier(key)) bad_spec(what, text, "bad parameter name '" + key + "'");
        if (!seen.insert(key).second) bad_spec(what, text, "parameter '" + key + "' given twice");
        if (std::find(text_keys.begin(), text_keys.end(), key) != text_keys.end()) {
            const bool quoted = value.size() >= 2 && value.front() == '"' && value.back() == '"' &&
                value.find('"', 1) == value.size() - 1;
            if (!quoted && !is_bare_text(value))
                bad_spec(what, text,
                         "value of '" + key +
                             "' must be text, bare (no blank, comma, parenthesis or "
                             "quote) or in double quotes, got '" +
                             value + "'");
            const std::string v = quoted ? value.substr(1, value.size() - 2) : value;
            if (v.empty()) bad_spec(what, text, "value of '" + key + "' is empty");
            spec.texts.emplace_back(key, v);
        } else {
            double v = 0.0;
            try {
                v = parse_double(value, "value of '" + key + "'");
            } catch (const input_error& e) {
                bad_spec(what, text, e.what());
            }
            spec.params.emplace_back(key, v);
        }
        if (end == body.size()) break;
        body.remove_prefix(end + 1);
    }
    return spec;
}

std::string format_spec(const NdfSpec& spec) {
    const auto& params = spec.params;
    std::string out = spec.name + "(";
    for (std::size_t i = 0; i < params.size(); ++i) {
        out += (i ? ", " : "") + params[i].first + "=" + format_shortest(params[i].second);
    }
    for (std::size_t i = 0; i < spec.texts.size(); ++i) {
        const std::string& v = spec.texts[i].second;
        out += (i || !params.empty() ? ", " : "") + spec.texts[i].first + "=" + (is_bare_text(v) ? v : '"' + v + '"');
    }
    return out + ")";
}

}  // namespace smithlab
