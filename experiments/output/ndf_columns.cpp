#include "output/ndf_columns.hpp"

#include <algorithm>

#include "smithlab/csv.hpp"

namespace smithlab::output {

namespace {
bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}
}  // namespace

NdfColumns ndf_columns(std::span<const AnyNdf> ndfs, const std::vector<std::string>& taken) {
    NdfColumns c;
    auto add = [&](const std::string& key) {
        if (!contains(taken, key) && !contains(c.names, key)) c.names.push_back(key);
    };
    for (const AnyNdf& n : ndfs) {
        for (const auto& [key, value] : n.parts().params) add(key);
        for (const auto& [key, text] : n.parts().texts) add(key);
    }
    return c;
}

std::vector<std::string> NdfColumns::cells(const AnyNdf& ndf) const {
    std::vector<std::string> out(names.size());
    for (std::size_t i = 0; i < names.size(); ++i) {
        for (const auto& [key, value] : ndf.parts().params)
            if (key == names[i]) out[i] = format_shortest(value);
        for (const auto& [key, text] : ndf.parts().texts)
            if (key == names[i]) out[i] = text;
    }
    return out;
}

}  // namespace smithlab::output
