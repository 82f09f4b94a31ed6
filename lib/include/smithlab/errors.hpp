/// @file
/// smithlab/errors.hpp -- the one exception type for bad input.
///
/// Out-of-domain parameters (alpha <= 0, NaN, gamma < 0, an unknown NDF, a malformed spec or CSV row) are errors,
/// never a silent NaN. Every message names the offending item.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace smithlab {

/// The message is kept as printable(message): an item echoed from a binary file (ESC, BEL, NUL, 0xFF) reaches a
/// terminal as `\x1b`, `\x07`, `\x00`, `\xff`, and a NUL cannot cut the message short.
struct input_error : std::invalid_argument {
    /// The error with `message`, kept as printable(message).
    /// @{
    explicit input_error(std::string_view message);
    explicit input_error(const char* message) : input_error(std::string_view(message)) {}
    explicit input_error(const std::string& message) : input_error(std::string_view(message)) {}
    /// @}
};

/// `text` with every byte that is neither printable ASCII, a tab, a newline nor part of a well-formed UTF-8 character
/// written as `\xNN` (two lowercase hex digits), and every backslash as itself: what a terminal shows of it is it.
std::string printable(std::string_view text);

/// Throws input_error("<what> must be <rule>, got <value>") unless ok. Allocates nothing when ok.
void require(bool ok, std::string_view what, std::string_view rule, double value);

/// The one strict reading of a number from text (option values, spec parameters): all of `text`, no blanks around it,
/// as a double, subnormals included. Throws input_error("<what> ...: '<text>'") saying which rule it breaks: not a
/// number, beyond the largest double (1.8e308), or a nonzero value below the smallest (4.9e-324), which would read
/// as 0. "nan" reads as NaN: the caller's own rule refuses it, naming the item.
double parse_double(std::string_view text, std::string_view what);

}  // namespace smithlab
