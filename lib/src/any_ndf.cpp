#include "smithlab/any_ndf.hpp"

#include "smithlab/errors.hpp"

namespace smithlab {

double AnyNdf::Lambda(double mu) const {
    if (!has_closed_Lambda()) throw input_error("ndf '" + spec_ + "' has no closed-form Lambda");
    return self_->closed(mu);
}

double AnyNdf::Lambda_spline(double mu) const {
    if (!has_spline_Lambda()) throw input_error("ndf '" + spec_ + "' has no spline Lambda");
    return self_->spline(mu);
}

double AnyNdf::Dcos_sf(double r2) const {
    if (!has_Dcos_sampler()) throw input_error("ndf '" + spec_ + "' has no analytic D cos sampler");
    return self_->Dcos_sf(r2);
}

double AnyNdf::Dcos_r2(double v) const {
    if (!has_Dcos_sampler()) throw input_error("ndf '" + spec_ + "' has no analytic D cos sampler");
    return self_->Dcos_r2(v);
}

double AnyNdf::param(std::string_view key) const {
    for (const auto& [k, v] : parts_.params)
        if (k == key) return v;
    throw input_error("ndf '" + spec_ + "' has no parameter '" + std::string(key) + "'");
}

bool AnyNdf::has_param(std::string_view key) const {
    for (const auto& [k, v] : parts_.params)
        if (k == key) return true;
    return false;
}

}  // namespace smithlab
