#include "smithlab/errors.hpp"
#include "smithlab/ndf.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace smithlab {

namespace {

// The length of the well-formed UTF-8 character at text[i] (RFC 3629: no overlong forms, no surrogates, at most
// U+10FFFF), or 0.
std::size_t utf8_length(std::string_view text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char b = byte(i);
    const std::size_t n = b >= 0xC2 && b <= 0xDF ? 2 : b >= 0xE0 && b <= 0xEF ? 3 : b >= 0xF0 && b <= 0xF4 ? 4 : 0;
    if (n == 0 || i + n > text.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
    const unsigned char b1 = byte(i + 1);
    if ((b == 0xE0 && b1 < 0xA0) || (b == 0xED && b1 > 0x9F) || (b == 0xF0 && b1 < 0x90) || (b == 0xF4 && b1 > 0x8F))
        return 0;
    return n;
}

}  // namespace

std::string printable(std::string_view text) {
    static constexpr char hex[] = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const unsigned char b = static_cast<unsigned char>(text[i]);
        if ((b >= 0x20 && b < 0x7F) || b == '\t' || b == '\n') {
            out += static_cast<char>(b);
            ++i;
        } else if (const std::size_t n = b >= 0x80 ? utf8_length(text, i) : 0; n > 0) {
            out.append(text.substr(i, n));
            i += n;
        } else {
            out += "\\x";
            out += hex[b >> 4];
            out += hex[b & 15];
            ++i;
        }
    }
    return out;
}

input_error::input_error(std::string_view message) : std::invalid_argument(printable(message)) {}

void require(bool ok, std::string_view what, std::string_view rule, double value) {
    if (ok) return;
    std::ostringstream msg;
    msg.precision(17);
    msg << what << " must be " << rule << ", got " << value;
    throw input_error(msg.str());
}

double parse_double(std::string_view text, std::string_view what) {
    const std::string s(text);  // strtod needs the terminating NUL
    auto refuse = [&](const char* why) -> double {
        throw input_error(std::string(what) + " " + why + ": '" + s + "'");
    };
    // strtod skips leading blanks; a number with blanks around it is refused at either end alike.
    if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return refuse("is not a number");
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size()) return refuse("is not a number");
    // ERANGE: overflow gives +-HUGE_VAL; underflow gives a subnormal (kept: it is the nearest double) or zero.
    if (errno == ERANGE && std::isinf(v)) return refuse("is beyond the largest double (1.8e308)");
    if (errno == ERANGE && v == 0.0) return refuse("is nonzero but below the smallest double (4.9e-324)");
    return v;
}

namespace detail {
void throw_nonfinite_D(double cos_theta_m, double d) {
    std::ostringstream msg;
    msg.precision(17);
    msg << "the NDF's D(cos_theta_m = " << cos_theta_m << ") returned " << d << "; D must be finite on [0, 1]";
    throw input_error(msg.str());
}
}  // namespace detail

}  // namespace smithlab
