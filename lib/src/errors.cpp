#include "smithlab/errors.hpp"
#include "smithlab/ndf.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace smithlab {

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
