// The report's references: which independent route a variant is measured against, and the cache that keeps them
// between runs of the same scene.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

#include "smithlab/any_ndf.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::report {

// A closed form where the NDF has one; otherwise a quadrature route other than the variant's own (the nested 2D
// route for the Boost 1D variants, Boost 1D at 1e-13 for the rest); never the route the variant is computed by
// (the closed-form row is checked by Boost 1D, the table by Boost 1D or 2D). Both agree with the test suite's 50-digit
// references to ~1e-15; GSL's QAG can stop at ~1e-11, so it is never a reference.
enum class Route { closed, q1d_boost, q2d_boost };

const char* name_of(Route r);
Route route_for(const LambdaVariant& v, const AnyNdf& ndf);
double compute_reference(const AnyNdf& ndf, double mu, Route r);
// input_error, before any work, unless every quadrature that the variant's row at (ndf, mu) runs (its reference's
// route, the variant's own) accepts mu.
void require_row_domain(const LambdaVariant& v, const AnyNdf& ndf, double mu);

// References by (spec, mu, route), read from and saved to a CSV file (DIR/cache/references.csv). Each record carries
// a check of its fields; one that does not match (cut short by a kill, edited) is discarded and computed again.
class ReferenceCache {
public:
    explicit ReferenceCache(std::filesystem::path file);
    double get(const AnyNdf& ndf, double mu, Route r);  // computes on a miss
    void save() const;
    std::size_t loaded() const { return loaded_; }
    std::size_t computed() const { return computed_; }
    std::size_t discarded() const { return discarded_; }

private:
    std::filesystem::path file_;
    std::map<std::string, double> values_;
    std::size_t loaded_ = 0, computed_ = 0, discarded_ = 0;
};

}  // namespace smithlab::report
