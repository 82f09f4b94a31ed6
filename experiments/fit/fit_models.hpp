// Fitting the diffuse models to one NDF family's data and measuring each on the validation set; the fits that look
// wrong are flagged (fit/fit_flags.hpp).
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "fit/fit_data.hpp"
#include "fit/fit_flags.hpp"
#include "fit/fit_results.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

// What the fits and their measures take from the scene.
struct FitSettings {
    std::vector<double> albedos;          // each point is fitted and measured at these
    double floor = 0.02;                  // the weights' relative floor (smithlab/fit/fit_model.hpp)
    std::vector<double> training_alphas;  // where the largest albedo and the grid checks are measured
    bool energy_bound = true;             // the fits held to a directional albedo <= 1 at the training alphas
    unsigned threads = 0;                 // the models are fitted on this many threads at once (0: all cores)
};

// Progress through the fits of every NDF on stderr: a line as each model starts (one fit may take tens of seconds,
// so each is announced), with the time since the fits began.
class FitProgress {
public:
    void starting(const std::string& ndf, std::size_t k, std::size_t n, const std::string& model) const;

private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// One NDF family's models as listed in the outputs (each at its starting constants where those are a model of its
// own, fit::DiffuseModel::own_baseline; each with free constants fitted, "<model>-fitted"), their errors on the
// validation set in the same order, and the flags of the fits.
struct NdfFits {
    std::vector<Measured> models;
    std::vector<ErrorRow> errors;
    std::vector<Flag> flags;
};

NdfFits fit_and_measure(const NdfData& data, const std::vector<const fit::DiffuseModel*>& models,
                        const FitSettings& settings, const FitProgress& progress);

}  // namespace smithlab::fit
