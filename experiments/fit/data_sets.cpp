#include "fit/data_sets.hpp"

#include <cmath>
#include <numbers>

#include "smithlab/rng.hpp"

namespace smithlab::fit {

const char* set_name(Set set) {
    static const char* const names[] = {"training", "validation", "albedo"};
    return names[set];
}

std::uint64_t data_stream(Set set, std::uint64_t ndf, std::uint64_t group, std::uint64_t point) {
    return set << 48 | ndf << 32 | group << 16 | point;
}

std::vector<fit::Directions> training_directions(const FitScene::Training& t) {
    std::vector<fit::Directions> d;
    for (std::size_t i = 0; i < t.theta.size(); ++i)
        for (std::size_t o = i; o < t.theta.size(); ++o) {
            if (t.theta[i] == 0.0 || t.theta[o] == 0.0) d.push_back({t.theta[i], t.theta[o], 0.0});
            else
                for (double phi : t.phi) d.push_back({t.theta[i], t.theta[o], phi});
        }
    return d;
}

std::vector<fit::Directions> validation_directions(std::uint64_t seed, std::uint64_t ndf, std::uint64_t group,
                                                   std::int64_t n) {
    const double deg = 180.0 / std::numbers::pi, c_min = std::cos(85.0 / deg);
    WalkRng g(seed, data_stream(validation_set, ndf, group, 0xffff), 0);
    auto theta = [&] { return std::acos(1.0 - uniform01(g) * (1.0 - c_min)) * deg; };
    std::vector<fit::Directions> d;
    for (std::int64_t k = 0; k < n; ++k) {
        const double ti = theta(), to = theta();
        d.push_back({ti, to, 180.0 * uniform01(g)});
    }
    return d;
}

std::vector<double> midpoints(const std::vector<double>& a) {
    if (a.size() < 2) return a;
    std::vector<double> m;
    for (std::size_t i = 0; i + 1 < a.size(); ++i) m.push_back(std::sqrt(a[i] * a[i + 1]));
    return m;
}

std::vector<Group> data_groups(const FitScene::Training& training, const FitScene::Validation& validation,
                               std::uint64_t seed, std::uint64_t ndf, const std::vector<double>& validation_alphas) {
    std::vector<Group> out;
    const std::vector<fit::Directions> train = training_directions(training);
    for (std::size_t a = 0; a < training.alpha.size(); ++a)
        out.push_back({training_set, a, training.alpha[a], train, training.walks});
    std::vector<fit::Directions> albedo_dirs;
    for (double t : validation.albedo_theta) albedo_dirs.push_back({t, 0.0, 0.0});
    for (std::size_t a = 0; a < validation_alphas.size(); ++a) {
        out.push_back({validation_set, a, validation_alphas[a], validation_directions(seed, ndf, a, validation.points),
                       validation.walks});
        out.push_back({albedo_set, a, validation_alphas[a], albedo_dirs, validation.albedo_walks});
    }
    return out;
}

}  // namespace smithlab::fit
