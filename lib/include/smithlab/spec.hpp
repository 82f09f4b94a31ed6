/// @file
/// smithlab/spec.hpp -- spec strings that name an NDF and its parameters: "gtr(alpha=0.3, gamma=1.5)".
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace smithlab {

/// A parsed spec: name(key=value, ...). Values are doubles, but for the keys a spec declares textual (a file's path:
/// "tabulated(file=ndf.csv)"). NDFs and facet materials are named this way.
struct NdfSpec {
    /// The NDF's or material's name.
    std::string name;
    /// The numeric parameters, as (key, value) in the order written.
    std::vector<std::pair<std::string, double>> params;
    /// The text parameters (the keys declared textual), as (key, text) in the order written.
    std::vector<std::pair<std::string, std::string>> texts = {};
};

/// Grammar: name [ "(" [ item { "," item } ] ")" ], item = key "=" value, blanks allowed between tokens; a name is an
/// identifier whose words may be joined by '-' ("fresnel-diffuse"). A value is a number, but for a key in text_keys:
/// there it is text, bare (no blank, comma, parenthesis or double quote in it) or in double quotes (any character but
/// a double quote). Throws input_error quoting `what` (the kind of spec, e.g. "material spec"), the text and the bad
/// part.
NdfSpec parse_spec(std::string_view text, std::string_view what = "ndf spec",
                   const std::vector<std::string>& text_keys = {});

/// A name or parameter key: a letter or '_' followed by letters, digits and '_'.
bool is_identifier(std::string_view s);

/// A spec's name: an identifier in which '-' may join words ("fresnel-diffuse").
bool is_spec_name(std::string_view s);
/// What a spec whose name is not one is told: "WHAT 'TEXT': " and this.
inline constexpr std::string_view spec_name_rule = "expected a name like ggx(alpha=0.2)";

/// "name(k1=v1, k2=v2, file=PATH)" with every number in its shortest round-trip form, then the texts (in double
/// quotes where bare text would not read back).
std::string format_spec(const NdfSpec& spec);

}  // namespace smithlab
