// How each fitted constant moves with a family's parameter, when a fit scene sweeps one (GTR's or the Student-t's
// gamma, any registered family's parameter other than its roughness) over three values or more.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_results.hpp"

namespace smithlab::fit {

// The fits of one family that differ in exactly one parameter: its values, fit by fit, in the scene's order.
struct ParameterSweep {
    std::string family, parameter;
    std::vector<std::size_t> fits;  // indices into Results::data
    std::vector<double> values;
};

// Every family of the results whose fits differ in one parameter, with at least min_fits fits, in scene order.
std::vector<ParameterSweep> parameter_sweeps(const Results& results, std::size_t min_fits);

// For each sweep of three fits or more: each constant of each fitted model as a line and as a parabola in the
// parameter, by weighted linear least squares in closed form (weights: the constants' standard errors; Eigen), with
// the coefficients' standard errors, chi^2 / dof and the largest deviation: DIR/FAMILY_PARAMETER_trends.csv and the
// Markdown tables returned ("" without such a sweep). A form fits where chi^2 / dof is near 1; a constant with a zero
// standard error gets no trend.
std::string write_parameter_trends(const std::filesystem::path& dir, const Results& results);

}  // namespace smithlab::fit
