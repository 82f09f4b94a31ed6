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

// A reference is one of reference_routes, the first that the NDF offers and that is not the route the variant takes
// on it (its LambdaRoute, route_on): the closed form where the NDF has one, else Boost 1D at 1e-13, else the
// nested 2D route at 1e-12 (the closed-form row is checked by Boost 1D, the table by Boost 1D or 2D, a Boost 1D
// variant by the closed form or the 2D route). The quadratures agree with the test suite's 50-digit references to
// ~1e-15; GSL's QAG can stop at ~1e-11, so it is never a reference.
inline constexpr LambdaRoute reference_routes[] = {LambdaRoute::closed, LambdaRoute::q1d_boost, LambdaRoute::q2d_boost};

// A reference route as the cache keys it: "closed", "q1d-boost-1e-13", "q2d-boost-1e-12".
const char* name_of(LambdaRoute r);
LambdaRoute route_for(const LambdaVariant& v, const AnyNdf& ndf);
double compute_reference(const AnyNdf& ndf, double mu, LambdaRoute r);  // r one of reference_routes
// input_error, before any work, unless every quadrature that the variant's row at (ndf, mu) runs (its reference's
// route, the variant's own) accepts mu.
void require_row_domain(const LambdaVariant& v, const AnyNdf& ndf, double mu);

// References by (spec, mu, route), read from and saved to a CSV file (DIR/cache/references.csv). Each record carries
// a check of its fields; one that does not match (cut short by a kill, edited) is discarded and computed again.
class ReferenceCache {
public:
    explicit ReferenceCache(std::filesystem::path file);
    double get(const AnyNdf& ndf, double mu, LambdaRoute r);  // computes on a miss
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
