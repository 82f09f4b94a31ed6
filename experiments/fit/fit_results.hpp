// What a fit run hands to its writers: each model as measured on each NDF family.
#pragma once

#include <string>
#include <vector>

#include "fit/fit_data.hpp"
#include "smithlab/fit/diffuse_models.hpp"

namespace smithlab::fitrun {

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

}  // namespace smithlab::fitrun
