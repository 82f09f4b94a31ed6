#include "smithlab/compensation/furnace.hpp"

#include <cmath>

#include "smithlab/compensation/compensation.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::compensation {

namespace {

// albedo(i, j, alpha, mu) at each point of the check grid with mu >= mu_min; the worst |albedo - 1| per alpha.
template <class Albedo>
std::vector<InterpolationError> furnace(const CheckedTable& t, double mu_min, const Albedo& albedo) {
    require(mu_min >= 0.0 && mu_min <= 1.0, "the furnace's least cosine", "in [0, 1]", mu_min);
    const AlbedoGrid& g = t.fine.grid;
    std::vector<InterpolationError> out(g.alphas.size());
    for (std::size_t i = 0; i < g.alphas.size(); ++i) {
        out[i].alpha = g.alphas[i];
        for (int j = 0; j < g.n_x; ++j) {
            const double mu = g.mu(i, j);
            if (mu < mu_min) continue;
            const double e = std::abs(albedo(i, j, g.alphas[i], mu) - 1.0);
            if (e >= out[i].max) out[i] = {e, g.alphas[i], mu};
        }
    }
    return out;
}

}  // namespace

std::vector<InterpolationError> kulla_conty_furnace(const CheckedTable& E, const std::vector<double>& missing,
                                                    double mu_min) {
    std::vector<double> lobe;  // per alpha: the lobe's albedo over 1 - E(mu_i), which does not depend on mu_i
    for (double alpha : E.fine.grid.alphas) lobe.push_back(kulla_conty_ratio(E.table, missing, alpha));
    return furnace(E, mu_min, [&](std::size_t i, int j, double alpha, double mu) {
        return E.fine.at(i, j) + lobe[i] * (1.0 - E.table.lookup(alpha, mu));
    });
}

std::vector<InterpolationError> turquin_furnace(const CheckedTable& sum, double mu_min) {
    return furnace(sum, mu_min, [&](std::size_t i, int j, double alpha, double mu) {
        return sum.fine.at(i, j) / sum.table.lookup(alpha, mu);
    });
}

InterpolationError worst_of(const std::vector<InterpolationError>& per_alpha) {
    InterpolationError w;
    for (const InterpolationError& e : per_alpha)
        if (e.max > w.max) w = e;
    return w;
}

}  // namespace smithlab::compensation
