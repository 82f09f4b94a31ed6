#include "smithlab/fit/albedo_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::fit {

double warp_cosine(double alpha, double mu) { return std::sqrt((1.0 + alpha) * mu / (mu + alpha)); }

double unwarp_cosine(double alpha, double x) {
    if (x >= 1.0) return 1.0;
    const double w = x * x;
    return alpha * w / ((1.0 + alpha) - w);
}

void AlbedoGrid::check() const {
    if (alphas.size() < 2) throw input_error("albedo table: needs 2 alphas or more (it interpolates between them)");
    for (std::size_t i = 0; i < alphas.size(); ++i) {
        require(alphas[i] > 0.0 && std::isfinite(alphas[i]), "albedo table: alpha", "finite and > 0", alphas[i]);
        if (i > 0 && !(alphas[i] > alphas[i - 1])) throw input_error("albedo table: alphas must ascend");
    }
    require(n_x >= 2, "albedo table: the number of cosines", ">= 2", n_x);
}

namespace {

// The cell of v in the ascending grid g (clamped to the end cells) and the weight of its upper end in [0, 1].
std::size_t cell(const std::vector<double>& g, double v, double& t) {
    if (!(v > g.front())) {
        t = 0.0;
        return 0;
    }
    if (!(v < g.back())) {
        t = 1.0;
        return g.size() - 2;
    }
    const std::size_t hi = static_cast<std::size_t>(std::upper_bound(g.begin(), g.end(), v) - g.begin());
    t = (v - g[hi - 1]) / (g[hi] - g[hi - 1]);
    return hi - 1;
}

std::vector<double> sqrt_of(const std::vector<double>& a) {
    std::vector<double> s(a.size());
    std::transform(a.begin(), a.end(), s.begin(), [](double v) { return std::sqrt(v); });
    return s;
}

// The refined alphas: refine steps of sqrt(alpha) between nodes.
std::vector<double> refined_alphas(const std::vector<double>& alphas, int refine) {
    std::vector<double> out;
    for (std::size_t i = 0; i + 1 < alphas.size(); ++i) {
        const double s0 = std::sqrt(alphas[i]), s1 = std::sqrt(alphas[i + 1]);
        out.push_back(alphas[i]);
        for (int k = 1; k < refine; ++k) {
            const double s = s0 + (s1 - s0) * k / refine;
            out.push_back(s * s);
        }
    }
    out.push_back(alphas.back());
    return out;
}

// Runs job(k) for k in [0, n) on `threads` threads (0: all cores), each k writing its own slots; the first exception
// is rethrown (util::reduce_blocks, with nothing to merge).
template <class Job>
void parallel_for(std::size_t n, unsigned threads, const Job& job) {
    util::reduce_blocks(
        n, threads, 0,
        [&](std::uint64_t k) {
            job(static_cast<std::size_t>(k));
            return 0;
        },
        [](int&, int) {}, [](std::uint64_t) {});
}

}  // namespace

double AlbedoTable::lookup(double alpha, double mu) const {
    require(alpha > 0.0 && std::isfinite(alpha), "alpha", "finite and > 0", alpha);
    require(mu >= 0.0 && mu <= 1.0, "mu = cos(theta)", "in [0, 1]", mu);
    const double x = warp_cosine(alpha, mu) * (grid.n_x - 1);
    const int j = std::min(static_cast<int>(x), grid.n_x - 2);
    const double tx = x - j;
    double ta = 0.0;
    const std::vector<double> s = sqrt_of(grid.alphas);
    const std::size_t i = cell(s, std::sqrt(alpha), ta);
    const double lo = at(i, j) + tx * (at(i, j + 1) - at(i, j));
    const double hi = at(i + 1, j) + tx * (at(i + 1, j + 1) - at(i + 1, j));
    return lo + ta * (hi - lo);
}

double lookup_alpha(const std::vector<double>& alphas, const std::vector<double>& values, double alpha) {
    require(alpha > 0.0 && std::isfinite(alpha), "alpha", "finite and > 0", alpha);
    if (alphas.size() < 2 || values.size() != alphas.size())
        throw input_error("albedo table: malformed (fewer than 2 alphas, or values of another size)");
    double t = 0.0;
    const std::size_t i = cell(sqrt_of(alphas), std::sqrt(alpha), t);
    return values[i] + t * (values[i + 1] - values[i]);
}

CheckedTable tabulate(const AlbedoGrid& grid, int refine, const AlbedoRow& row, unsigned threads) {
    grid.check();
    require(refine >= 1, "the check grid's refinement", ">= 1", refine);
    CheckedTable out;
    out.fine.grid = {refined_alphas(grid.alphas, refine), refine * (grid.n_x - 1) + 1};
    const std::size_t na = out.fine.grid.alphas.size(), nx = static_cast<std::size_t>(out.fine.grid.n_x);
    out.fine.values.assign(na * nx, 0.0);
    parallel_for(na, threads, [&](std::size_t i) {
        const std::function<double(double)> f = row(out.fine.grid.alphas[i]);
        for (std::size_t j = 0; j < nx; ++j) {
            const double v = f(out.fine.grid.mu(i, static_cast<int>(j)));
            if (!std::isfinite(v))
                throw std::runtime_error("albedo table: a value that is not finite at alpha " +
                                         format_shortest(out.fine.grid.alphas[i]));
            out.fine.values[i * nx + j] = v;
        }
    });
    out.table.grid = grid;
    const auto r = static_cast<std::size_t>(refine);
    for (std::size_t i = 0; i < grid.alphas.size(); ++i)
        for (int j = 0; j < grid.n_x; ++j) out.table.values.push_back(out.fine.at(i * r, static_cast<int>(j * r)));
    for (std::size_t i = 0; i < na; ++i)
        for (std::size_t j = 0; j < nx; ++j) {
            const double alpha = out.fine.grid.alphas[i], mu = out.fine.grid.mu(i, static_cast<int>(j));
            const double e = std::abs(out.table.lookup(alpha, mu) - out.fine.values[i * nx + j]);
            if (e > out.error.max) out.error = {e, alpha, mu};
        }
    return out;
}

InterpolationError alpha_interpolation_error(const std::vector<double>& fine_alphas, const std::vector<double>& fine,
                                             int refine) {
    std::vector<double> alphas, values;
    for (std::size_t i = 0; i < fine_alphas.size(); i += static_cast<std::size_t>(refine)) {
        alphas.push_back(fine_alphas[i]);
        values.push_back(fine[i]);
    }
    InterpolationError worst;
    for (std::size_t i = 0; i < fine_alphas.size(); ++i) {
        const double e = std::abs(lookup_alpha(alphas, values, fine_alphas[i]) - fine[i]);
        if (e > worst.max) worst = {e, fine_alphas[i], 0.0};
    }
    return worst;
}

InterpolationError below_grid_error(const CheckedTable& t, const AlbedoRow& row, const std::vector<double>& factors,
                                    unsigned threads) {
    std::vector<InterpolationError> each(factors.size());
    parallel_for(factors.size(), threads, [&](std::size_t k) {
        require(factors[k] > 0.0 && factors[k] < 1.0, "a below-grid factor", "in (0, 1)", factors[k]);
        const double alpha = t.table.grid.alphas.front() * factors[k];
        const std::function<double(double)> f = row(alpha);
        for (int j = 0; j < t.fine.grid.n_x; ++j) {
            const double mu = unwarp_cosine(alpha, t.fine.grid.x(j));
            const double e = std::abs(t.table.lookup(alpha, mu) - f(mu));
            if (e > each[k].max) each[k] = {e, alpha, mu};
        }
    });
    InterpolationError worst;
    for (const InterpolationError& e : each)
        if (e.max > worst.max) worst = e;
    return worst;
}

}  // namespace smithlab::fit
