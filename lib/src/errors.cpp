#include "smithlab/errors.hpp"
#include "smithlab/ndf.hpp"

#include <sstream>

namespace smithlab {

void require(bool ok, std::string_view what, std::string_view rule, double value) {
    if (ok) return;
    std::ostringstream msg;
    msg.precision(17);
    msg << what << " must be " << rule << ", got " << value;
    throw input_error(msg.str());
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
