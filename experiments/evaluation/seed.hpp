// The seed of a random stream as both front ends take it: the command line's --seed text, the Python module's seed
// argument (an int, or its text).
#pragma once

#include <string>

namespace smithlab::evaluation {

// Parses a seed: decimal digits only, 0 .. 2^64 - 1 (no sign, no wrap-around); anything else is an input_error naming
// `what`.
unsigned long long parse_seed(const std::string& text, const std::string& what);

}  // namespace smithlab::evaluation
