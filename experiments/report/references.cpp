#include "references.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "smithlab/csv.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

const char* name_of(Route r) {
    return r == Route::closed ? "closed" : r == Route::q1d_boost ? "q1d-boost-1e-13" : "q2d-boost-1e-12";
}

Route route_for(const LambdaVariant& v, const AnyNdf& ndf) {
    // Never the route a variant is computed by: the closed form is checked by Boost 1D; the table, built from the
    // closed form where there is one and else from Boost 1D, by Boost 1D or the nested 2D route.
    const bool closed = ndf.has_closed_Lambda();
    if (v.name == "closed-form") return Route::q1d_boost;
    if (v.name == "table") return closed ? Route::q1d_boost : Route::q2d_boost;
    if (closed) return Route::closed;
    return v.name.rfind("q1d-boost", 0) == 0 ? Route::q2d_boost : Route::q1d_boost;
}

double compute_reference(const AnyNdf& ndf, double mu, Route r) {
    switch (r) {
        case Route::closed: return ndf.Lambda(mu);
        case Route::q1d_boost: return Lambda_1d(ndf, mu, {Backend::boost, 1e-13});
        case Route::q2d_boost: return Lambda_2d(ndf, mu, {Backend::boost, 1e-12});
    }
    return NAN;
}

ReferenceCache::ReferenceCache(fs::path file) : file_(std::move(file)) {
    std::ifstream in(file_);
    if (!in) return;
    const auto records = read_csv(in);
    for (std::size_t i = 1; i < records.size(); ++i)
        if (records[i].error.empty() && records[i].fields.size() == 4)
            values_[records[i].fields[0] + "|" + records[i].fields[1] + "|" + records[i].fields[2]] =
                std::strtod(records[i].fields[3].c_str(), nullptr);
    loaded_ = values_.size();
}

double ReferenceCache::get(const AnyNdf& ndf, double mu, Route r) {
    const std::string key = ndf.spec() + "|" + format_g17(mu) + "|" + name_of(r);
    if (auto it = values_.find(key); it != values_.end()) return it->second;
    ++computed_;
    return values_[key] = compute_reference(ndf, mu, r);
}

void ReferenceCache::save() const {
    fs::create_directories(file_.parent_path());
    std::ofstream out(file_);
    write_csv_record(out, {"spec", "mu", "route", "lambda"});
    for (const auto& [key, v] : values_) {
        const auto a = key.find('|'), b = key.find('|', a + 1);
        write_csv_record(out, {key.substr(0, a), key.substr(a + 1, b - a - 1), key.substr(b + 1), format_g17(v)});
    }
}

}  // namespace smithlab::report
