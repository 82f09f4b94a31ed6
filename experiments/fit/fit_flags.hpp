// Fits that look wrong, flagged in report.md and on stderr: a fitted constant at or beyond the range where its model
// means what its source says (fit::DiffuseModel::ranges), or a fit that measures worse on the validation set than
// the model at its starting constants (its RMS relative error, RMS error of the directional albedo, or chi^2 / value:
// the fit minimizes chi^2 on the training set, so a worse validation error says the model cannot follow the data
// there and the fit traded one error for another).
#pragma once

#include <string>
#include <vector>

#include "fit/fit_results.hpp"

namespace smithlab::fit {

struct Flag {
    std::string model, ndf;
    std::string what;  // "sigma_scale = 14.965 is beyond its range [0, 1.5708]: ..."
};

// The flags of one fit: its constants against their ranges, its errors against those at its starting constants.
std::vector<Flag> flag_fit(const Measured& fitted, const ErrorRow& errors, const ErrorRow& at_start);

// report.md's section: what a flag means and every flag ("None" when there is none).
std::string flags_markdown(const std::vector<Flag>& flags);

// One warning line per flag on stderr.
void print_flags(const std::vector<Flag>& flags);

}  // namespace smithlab::fit
