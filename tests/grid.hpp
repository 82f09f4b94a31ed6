// tests/grid.hpp -- the parameter grids the accuracy tests sweep: the accepted domain, stiff corners included.
#pragma once

#include <cmath>
#include <vector>

namespace grid {

// n points from lo to hi, evenly spaced in log.
inline std::vector<double> logspace(double lo, double hi, int n) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i) v.push_back(lo * std::pow(hi / lo, i / double(n - 1)));
    return v;
}

inline const std::vector<double> alphas = {1e-4, 3e-4, 1e-3, 0.01, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999999, 1.0};
inline const std::vector<double> mus = logspace(1e-4, 1e4, 17);

}  // namespace grid
