// How each fitted constant moves with GTR's gamma, when a fit scene has three or more gammas.
#pragma once

#include <filesystem>
#include <string>

#include "fit_results.hpp"

namespace smithlab::fitrun {

// Each constant of each fitted model as a line and as a parabola in gamma, by weighted linear least squares in closed
// form (weights: the constants' standard errors; Eigen), with the coefficients' standard errors, chi^2 / dof and the
// largest deviation: DIR/gamma_trends.csv and the Markdown table returned ("" with fewer than three GTR gammas). A
// form fits where chi^2 / dof is near 1; a constant with a zero standard error gets no trend.
std::string write_gamma_trends(const std::filesystem::path& dir, const Results& results);

}  // namespace smithlab::fitrun
