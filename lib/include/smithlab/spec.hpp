// smithlab/spec.hpp -- spec strings that name an NDF and its parameters: "gtr(alpha=0.3, gamma=1.5)".
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace smithlab {

// A parsed spec: name(key=value, ...). Values are doubles. NDFs and facet materials are named this way.
struct NdfSpec {
    std::string name;
    std::vector<std::pair<std::string, double>> params;
};

// Grammar: name [ "(" [ key "=" number { "," key "=" number } ] ")" ], blanks allowed between tokens; a name is an
// identifier whose words may be joined by '-' ("fresnel-diffuse"). Throws input_error quoting `what` (the kind of
// spec, e.g. "material spec"), the text and the bad part.
NdfSpec parse_spec(std::string_view text, std::string_view what = "ndf spec");

// A name or parameter key: a letter or '_' followed by letters, digits and '_'.
bool is_identifier(std::string_view s);

// A spec's name: an identifier in which '-' may join words ("fresnel-diffuse").
bool is_spec_name(std::string_view s);
// What a spec whose name is not one is told: "WHAT 'TEXT': " and this.
inline constexpr std::string_view spec_name_rule = "expected a name like ggx(alpha=0.2)";

// "name(k1=v1, k2=v2)" with every value in its shortest round-trip form.
std::string format_spec(const NdfSpec& spec);

}  // namespace smithlab
