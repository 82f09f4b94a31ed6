// The GTR family evaluator (family.hpp): the generated trees and their stated bounds, and the checked calls.
#include "smithlab/gtr/family.hpp"

#include "smithlab/errors.hpp"

namespace smithlab {

const GtrFamily& GtrFamily::get() {
    static const GtrFamily family;
    return family;
}

GtrFamily::GtrFamily() : data_(gtr_family_data) {
    for (int c = 0; c < 2; ++c)
        for (int d = 0; d < 3; ++d) inv_step_[c][d] = inv_step(c, d);
    mu_lo_rel_ = std::exp(xi_lo);
    // the leaves are checked to twice the tolerances on their 3 x 3 x 3 grids (family_gen.cpp)
    error_bound_ = 2.0 * tolerance + data_.asymptote_bound;
    G1_error_bound_ = 2.0 * G1_tolerance + data_.asymptote_bound / 4;
}

void require_gtr_family_domain(double alpha, double gamma) {
    require(GtrFamily::alpha_in_domain(alpha), "family: alpha", "in [1e-4, 1]", alpha);
    require(GtrFamily::gamma_in_domain(gamma), "family: gamma", "in [0, 20]", gamma);
}

double Lambda_gtr_family(double alpha, double gamma, double mu, Downward downward) {
    require_gtr_family_domain(alpha, gamma);
    const GtrFamily& t = GtrFamily::get();
    return Lambda_at(mu, downward, [&](double m) { return t.Lambda_up(alpha, gamma, m); });
}

double G1_gtr_family(double alpha, double gamma, double mu) {
    require_gtr_family_domain(alpha, gamma);
    const GtrFamily& t = GtrFamily::get();
    return 1.0 / (1.0 + Lambda_of_abs(mu, [&](double m) { return t.Lambda_up(alpha, gamma, m); }));
}

}  // namespace smithlab
