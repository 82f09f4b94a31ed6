// smithlab/errors.hpp -- the one exception type for bad input.
//
// Out-of-domain parameters (alpha <= 0, NaN, gamma < 0, an unknown NDF, a malformed spec or CSV row) are errors,
// never a silent NaN. Every message names the offending item.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace smithlab {

struct input_error : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

// Throws input_error("<what> must be <rule>, got <value>") unless ok. Allocates nothing when ok.
void require(bool ok, std::string_view what, std::string_view rule, double value);

}  // namespace smithlab
