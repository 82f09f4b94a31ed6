// The fitter's traced sets and their layout (the job plan): for each NDF family, one group per alpha of each set
// (training, validation, directional albedo), its points' directions, and each point's random stream.
//
// Point j of group g of NDF n draws its walks from WalkRng(seed, stream, k), stream = set << 48 | n << 32 | g << 16 |
// j: the same bits for any --threads, resumed or not.
#pragma once

#include <cstdint>
#include <vector>

#include "fit/fit_scene.hpp"
#include "smithlab/fit/dataset.hpp"

namespace smithlab::fit {

enum Set : std::uint64_t { training_set = 0, validation_set = 1, albedo_set = 2 };
const char* set_name(Set set);  // "training", "validation", "albedo"

// One alpha of one set: its points' directions, traced together on one microsurface.
struct Group {
    Set set;
    std::uint64_t index;  // the alpha's place in its set
    double alpha;
    std::vector<fit::Directions> dirs;
    std::int64_t walks;
};

std::uint64_t data_stream(Set set, std::uint64_t ndf, std::uint64_t group, std::uint64_t point);

// theta_i <= theta_o from the axis, every phi (one where either is 0: phi means nothing there).
std::vector<fit::Directions> training_directions(const FitScene::Training& training);

// n pairs uniform in solid angle up to 85 degrees, phi in [0, 180], from the scene's seed (a stream of its own:
// point 0xffff of the validation group, beyond the points a group holds).
std::vector<fit::Directions> validation_directions(std::uint64_t seed, std::uint64_t ndf, std::uint64_t group,
                                                   std::int64_t n);

// The geometric midpoints of consecutive alphas (the validation alphas; a single alpha is its own).
std::vector<double> midpoints(const std::vector<double>& alphas);

// NDF n's groups: the training set's alphas, then per validation alpha its random pairs and its directional albedos.
std::vector<Group> data_groups(const FitScene::Training& training, const FitScene::Validation& validation,
                               std::uint64_t seed, std::uint64_t ndf, const std::vector<double>& validation_alphas);

}  // namespace smithlab::fit
