// smithlab/fast_lambda.hpp -- Lambda of one NDF at the cost of a closed form, for the code that calls it per sample
// or per bounce (samplers, the microsurface walk): the NDF's closed form when it has one (checked at run time, so that
// GTR at a non-integer gamma takes the other branch), else its LambdaTable (lambda_table.hpp), built once here.
// Read-only after construction, so any number of threads may call it.
#pragma once

#include <cmath>
#include <optional>

#include "smithlab/lambda_table.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

template <Ndf N>
class FastLambda {
public:
    explicit FastLambda(const N& ndf, const LambdaTableOptions& table = {}) : ndf_(ndf) {
        if (!has_closed_Lambda(ndf_)) table_.emplace(tabulate_Lambda(ndf_, table));
    }

    // Lambda(mu) for mu >= 0 (mu = 0: inf; mu = inf: 0). Downward directions are the caller's convention
    // (smith.hpp, downward_Lambda).
    double operator()(double mu) const {
        if (table_) return table_->Lambda(mu);
        return smithlab::Lambda(ndf_, mu);  // the closed form, with 0 and inf exact
    }
    bool tabulated() const { return table_.has_value(); }
    double error_estimate() const { return table_ ? table_->error_estimate() : 0.0; }  // relative
    const N& ndf() const { return ndf_; }

private:
    N ndf_;
    std::optional<LambdaTable> table_;
};

}  // namespace smithlab
