#include "evaluation/seed.hpp"

#include <cerrno>
#include <cstdlib>

#include "smithlab/errors.hpp"

namespace smithlab::evaluation {

unsigned long long parse_seed(const std::string& text, const std::string& what) {
    errno = 0;
    const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
    const unsigned long long v = digits ? std::strtoull(text.c_str(), nullptr, 10) : 0;
    if (!digits || errno == ERANGE)
        throw input_error(what + " must be an integer in [0, 18446744073709551615], got '" + text + "'");
    return v;
}

}  // namespace smithlab::evaluation
