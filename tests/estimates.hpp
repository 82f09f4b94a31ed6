// Monte Carlo estimates compared in the tests: the distance of two independent estimates in units of their combined
// standard error.
#pragma once

#include <cmath>
#include <smithlab/walk/tally.hpp>

namespace smithlab_test {

/// |a - b| / sqrt(se_a^2 + se_b^2): a z-score of two independent estimates of the same value.
inline double sigmas(const smithlab::walk::Estimate& a, const smithlab::walk::Estimate& b) {
    return std::abs(a.value - b.value) / std::hypot(a.stderr_, b.stderr_);
}

}  // namespace smithlab_test
