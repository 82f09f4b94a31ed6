// What a fit run hands to its writers: each model as measured on each NDF family, and its errors on the validation set.
#pragma once

#include <string>
#include <vector>

#include "fit/fit_data.hpp"
#include "smithlab/fit/diffuse_model.hpp"
#include "smithlab/fit/fit_model.hpp"

namespace smithlab::fit {

// A model as measured: its name in the outputs ("<model>" at its published constants, "<model>-fitted" refitted),
// the model, its constants (and their standard errors when fitted).
struct Measured {
    std::string name;
    const fit::DiffuseModel* model;
    std::vector<double> params, stderr_;
    double chi2_dof_training = 0.0;
    int iterations = 0;
    bool fitted() const { return !stderr_.empty(); }
};

// fits[n] are the models measured on data[n]; every NDF has the same models in the same order.
struct Results {
    std::vector<NdfData> data;
    std::vector<std::vector<Measured>> fits;
};

// One row of errors.csv: a model (a fixed baseline, a model at its published constants, or "<model>-fitted") on one
// NDF family, measured on the validation set.
struct ErrorRow {
    std::string model, ndf;
    double rms_rel, max_rel, albedo_rms, chi2_dof;
    fit::AlbedoPeak peak;  // the largest directional albedo at albedo 1 (training alphas x theta_i 0..89)
    fit::GridCheck grid;   // the largest relative |f(l, v) - f(v, l)|, the smallest f
};

}  // namespace smithlab::fit
