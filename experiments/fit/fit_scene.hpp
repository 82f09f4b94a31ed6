// The diffuse fitter's scene file (TOML, read strictly: scene/strict_table.hpp): the facets traced, the NDF families,
// the training and validation sets, the albedos, models and weights of the fit, and the compensation tables.
// experiments/scenes/fit_default.toml documents every key and is the embedded default.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compensation/settings.hpp"
#include "scene/alpha_family.hpp"
#include "scene/limits.hpp"
#include "smithlab/fit/diffuse_registry.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::fit {

// One fitted NDF: a family at fixed parameters, swept over the training set's alpha (scene/alpha_family.hpp).
using FitFamily = scene::AlphaFamily;

struct FitScene {
    std::string title = "smithlab fit";
    std::string material = "fresnel-diffuse(f0=0.04, albedo=1)";
    std::vector<double> albedos{0.25, 0.5, 0.75, 1.0};
    // The models fitted, in the scene's order, or every registered one where it names none: the parse's registry's.
    std::vector<const fit::DiffuseModel*> models;
    double floor = 0.02;
    bool energy_bound = true;  // fitted models held to a directional albedo <= 1 (fit_model.hpp)
    std::uint64_t seed = 1;
    // The eval estimator of every traced point (walk.hpp; all unbiased, the default the lowest equal-error time).
    walk::EvalEstimator estimator = fit::fit_estimator;
    std::vector<FitFamily> ndfs;  // the [[ndf]] axes expanded: one entry per fitted NDF
    struct Training {
        std::vector<double> alpha, theta, phi;
        std::int64_t walks = 20000;
    } training;
    struct Validation {
        std::int64_t points = 40;  // random direction pairs per validation alpha
        std::int64_t walks = 20000;
        std::vector<double> albedo_theta{0.0, 30.0, 50.0, 65.0, 80.0};
        std::int64_t albedo_walks = 100000;
    } validation;
    // The energy-compensation tables (compensation/stage.hpp): absent (enabled = false) unless the scene has
    // [compensation].
    compensation::Settings compensation;
    // The pictures (fit_pictures.hpp): absent (enabled = false) unless the scene has [pictures].
    struct Pictures {
        bool enabled = false;
        std::vector<double> sphere_alpha{0.001, 0.0625, 0.25, 0.5625, 1.0};  // Hammon's columns (0 drawn at 0.001)
        std::int64_t pixels = 32;                                            // a sphere's diameter in pixels
        std::int64_t walks = 2000;                                           // per simulated pixel or slice point
        std::vector<double> slice_alpha{0.25, 1.0};
        std::int64_t slice_n = 24;  // (theta_h, theta_d) points per side of a slice
    } pictures;
};

// Refuses (input_error "SOURCE:LINE: key ...") an unknown key or section, a value of the wrong type, a material that
// is not lambert or fresnel-diffuse at albedo 1, an albedo outside [1e-100, 1], a model `models` does not hold, a floor
// outside [0, 1), alpha outside (0, 1], theta outside [0, 90), an integer out of its bounds (validation.points in
// [1, 65534]), more than 65535 training direction pairs per alpha (each point's random stream holds its index in 16
// bits), an [[ndf]] whose family is not registered, a parameter the family does not have, or an axis for its
// roughness (alpha is the training set's). Each NDF's values are checked by the registry when the run prepares them.
// The fit's size is checked as its [[ndf]] entries are read, before their NDFs are made: points (training direction
// pairs x alpha, validation points and albedo directions x validation alpha, per NDF) beyond limits.max_cells or
// walks in all beyond limits.max_walks are refused at the entry that passes the bound (scene/limits.hpp); so is a
// [compensation] whose tables (each value of E counted as the walks of its time, compensation/settings.cpp) and furnace
// walks, with the fit's, pass limits.max_walks.
FitScene parse_fit_scene(const std::string& text, const std::string& source, const NdfRegistry& registry,
                         const scene::SizeLimits& limits = {});

const std::string& default_fit_scene_text();

}  // namespace smithlab::fit
