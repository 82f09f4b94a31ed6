#include "smithlab/errors.hpp"

#include <sstream>

namespace smithlab {

void require(bool ok, const std::string& what, const std::string& rule, double value) {
    if (ok) return;
    std::ostringstream msg;
    msg.precision(17);
    msg << what << " must be " << rule << ", got " << value;
    throw input_error(msg.str());
}

}  // namespace smithlab
