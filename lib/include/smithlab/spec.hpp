// smithlab/spec.hpp -- spec strings that name an NDF and its parameters: "gtr(alpha=0.3, gamma=1.5)".
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace smithlab {

// A parsed spec: name(key=value, ...). Values are doubles.
struct NdfSpec {
    std::string name;
    std::vector<std::pair<std::string, double>> params;
};

// Grammar: name [ "(" [ key "=" number { "," key "=" number } ] ")" ], blanks allowed between tokens.
NdfSpec parse_spec(std::string_view text);  // throws input_error quoting the text and the bad part

// A name or parameter key: a letter or '_' followed by letters, digits and '_'.
bool is_identifier(std::string_view s);

// "name(k1=v1, k2=v2)" with every value in its shortest round-trip form.
std::string format_spec(const NdfSpec& spec);

}  // namespace smithlab
