#include "scene/value_checks.hpp"

#include "smithlab/csv.hpp"

namespace smithlab::scene {

std::vector<double> read_bounded(StrictTable& t, const std::string& key, double lo, double hi, bool open_lo,
                                 bool open_hi, const std::string& range) {
    const std::vector<double> v = read_axis(t, key);
    for (double x : v)
        if (!((open_lo ? x > lo : x >= lo) && (open_hi ? x < hi : x <= hi)))
            t.fail(key, "values must be in " + range + ", got " + format_shortest(x));
    return v;
}

}  // namespace smithlab::scene
