// Checks of a scene's lists that several scene formats share (fit, tables): each refusal names the key.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "scene/strict_table.hpp"

namespace smithlab::scene {

// Refuses a list that names one thing twice (equal as values: 1.5 and 1.50, or one conductor spelled two ways).
template <class T, class Describe>
void refuse_repeats(const StrictTable& t, const std::string& key, const std::vector<T>& v, Describe describe) {
    for (std::size_t i = 0; i < v.size(); ++i)
        if (std::find(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v[i]) !=
            v.begin() + static_cast<std::ptrdiff_t>(i))
            t.fail(key, "names " + describe(v[i]) + " twice");
}

// An axis (read_axis) whose values lie in [lo, hi], either end open; `range` says which in the message.
std::vector<double> read_bounded(StrictTable& t, const std::string& key, double lo, double hi, bool open_lo,
                                 bool open_hi, const std::string& range);

}  // namespace smithlab::scene
