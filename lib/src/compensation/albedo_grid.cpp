#include "smithlab/compensation/albedo_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::compensation {

namespace {
// The warp's scale in lookup_power_law's messages.
constexpr const char* warp_scale_name = "the warp's scale";
}  // namespace

double warp_cosine(double c, double mu) { return std::sqrt((1.0 + c) * mu / (mu + c)); }

double unwarp_cosine(double c, double x) {
    if (x >= 1.0) return 1.0;
    const double w = x * x;
    return c * w / ((1.0 + c) - w);
}

double NodeCluster::coordinate(double mu) const {
    const double lo = std::asinh(this->mu / width), hi = std::asinh((1.0 - this->mu) / width);
    return (std::asinh((mu - this->mu) / width) + lo) / (lo + hi);
}

void NodeCluster::check() const {
    require(mu >= 0.0 && mu <= 1.0, "a node cluster's cosine", "in [0, 1]", mu);
    require(width > 0.0 && std::isfinite(width), "a node cluster's width", "finite and > 0", width);
    require(weight >= 0.0 && weight < 1.0, "a node cluster's share of the axis", "in [0, 1)", weight);
}

double AlbedoGrid::x_of(double c, double mu) const {
    const double b = cluster.weight;
    return b == 0.0 ? warp_cosine(c, mu) : (1.0 - b) * warp_cosine(c, mu) + b * cluster.coordinate(mu);
}

double AlbedoGrid::mu_of(double c, double x) const {
    if (cluster.weight == 0.0) return unwarp_cosine(c, x);
    if (x <= 0.0) return 0.0;
    if (x >= 1.0) return 1.0;
    double lo = 0.0, hi = 1.0;  // x_of is increasing: bisection to adjacent doubles
    for (double m = 0.5; m > lo && m < hi; m = 0.5 * (lo + hi)) (x_of(c, m) < x ? lo : hi) = m;
    return 0.5 * (lo + hi);
}

double AlbedoGrid::scale(double alpha) const { return lookup_power_law(alphas, scales, alpha, warp_scale_name); }

double masking_cot(FunctionRef Lambda) {
    constexpr double Lambda_dip = 0.3;  // measured (albedo_grid.hpp): the dip of E lies near it
    double lo = 1e-30, hi = 1e30;       // Lambda(lo) > Lambda_dip > Lambda(hi)
    if (!(Lambda(lo) > Lambda_dip && Lambda(hi) < Lambda_dip))
        throw input_error("the masking slope: Lambda does not cross 0.3 for cot(theta) in [1e-30, 1e30]");
    while (hi / lo > 1.0 + 1e-12) {
        const double m = std::sqrt(lo * hi);
        (Lambda(m) > Lambda_dip ? lo : hi) = m;
    }
    return std::sqrt(lo * hi);
}

double warp_scale(double cot) {
    // Six times the cosine of the dip spreads the nodes over it and keeps the warp mild near mu = 1 at large alpha
    // (measured, albedo_grid.hpp).
    constexpr double factor = 6.0;
    return factor * cot / std::sqrt(1.0 + cot * cot);
}

void AlbedoGrid::check() const {
    if (alphas.size() < 2) throw input_error("albedo table: needs 2 alphas or more (it interpolates between them)");
    for (std::size_t i = 0; i < alphas.size(); ++i) {
        require(alphas[i] > 0.0 && std::isfinite(alphas[i]), "albedo table: alpha", "finite and > 0", alphas[i]);
        if (i > 0 && !(alphas[i] > alphas[i - 1])) throw input_error("albedo table: alphas must ascend");
    }
    if (scales.size() != alphas.size())
        throw input_error("albedo table: " + std::to_string(scales.size()) + " warp scales for " +
                          std::to_string(alphas.size()) + " alphas");
    for (double c : scales) require(c > 0.0 && std::isfinite(c), "albedo table: a warp scale", "finite and > 0", c);
    require(n_x >= 2, "albedo table: the number of cosines", ">= 2", n_x);
    cluster.check();
}

namespace {

// The cell i of alpha among the ascending alphas (clamped to the end cells) and the weight t of its upper end in
// [0, 1], linear in sqrt(alpha) (the cell is the same found in alpha or in its root: the root is monotone).
struct AlphaCell {
    std::size_t i = 0;
    double t = 0.0;
};

AlphaCell cell(const std::vector<double>& alphas, double alpha) {
    if (!(alpha > alphas.front())) return {0, 0.0};
    if (!(alpha < alphas.back())) return {alphas.size() - 2, 1.0};
    const std::size_t hi =
        static_cast<std::size_t>(std::upper_bound(alphas.begin(), alphas.end(), alpha) - alphas.begin());
    const double s0 = std::sqrt(alphas[hi - 1]), s1 = std::sqrt(alphas[hi]);
    return {hi - 1, (std::sqrt(alpha) - s0) / (s1 - s0)};
}

// input_error unless there are 2 alphas or more and one value each (lookup_power_law's values).
void require_one_value_each(const std::vector<double>& alphas, const std::vector<double>& values, const char* what) {
    if (alphas.size() < 2 || values.size() != alphas.size())
        throw input_error(std::string(what) +
                          " over alpha: malformed (fewer than 2 alphas, or values of another size)");
}

// lookup_power_law at alpha, whose cell among the alphas is i; input_error unless the cell's two values are finite
// and > 0.
double power_law_in_cell(const std::vector<double>& alphas, const std::vector<double>& values, double alpha,
                         std::size_t i, const char* what) {
    for (std::size_t k : {i, i + 1})
        require(values[k] > 0.0 && std::isfinite(values[k]), what, "finite and > 0", values[k]);
    // ln v linear in ln alpha; below the first node the first cell's line continued, above the last the last value.
    const double u = alpha < alphas.back() ? std::log(alpha / alphas[i]) / std::log(alphas[i + 1] / alphas[i]) : 1.0;
    if (u == 0.0 || u == 1.0) return values[u == 0.0 ? i : i + 1];  // a node's own value, not exp(ln v)
    return std::exp(std::log(values[i]) + u * (std::log(values[i + 1]) - std::log(values[i])));
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
    const char* what = warp_scale_name;
    require_one_value_each(grid.alphas, grid.scales, what);
    // One search for alpha's cell: the scale's interpolation (grid.scale) and the values' weight ta.
    const auto [i, ta] = cell(grid.alphas, alpha);
    const double x = grid.x_of(power_law_in_cell(grid.alphas, grid.scales, alpha, i, what), mu) * (grid.n_x - 1);
    const int j = std::min(static_cast<int>(x), grid.n_x - 2);
    const double tx = x - j;
    const double lo = at(i, j) + tx * (at(i, j + 1) - at(i, j));
    const double hi = at(i + 1, j) + tx * (at(i + 1, j + 1) - at(i + 1, j));
    const double v = lo + ta * (hi - lo);
    return stored == Stored::log ? std::exp(v) : v;
}

std::vector<CheckedTable> tabulate(const AlbedoGrid& grid, int refine, const std::vector<Stored>& stored,
                                   const AlbedoRows& rows, unsigned threads) {
    grid.check();
    require(refine >= 1, "the check grid's refinement", ">= 1", refine);
    if (stored.empty()) throw input_error("albedo table: no albedo to tabulate");
    AlbedoGrid fine{refined_alphas(grid.alphas, refine), {}, refine * (grid.n_x - 1) + 1, grid.cluster};
    for (double a : fine.alphas) fine.scales.push_back(grid.scale(a));
    const std::size_t na = fine.alphas.size(), nx = static_cast<std::size_t>(fine.n_x);
    const std::size_t nv = stored.size();
    std::vector<CheckedTable> out(nv);
    for (std::size_t k = 0; k < nv; ++k) {
        out[k].fine.grid = fine;
        out[k].fine.values.assign(na * nx, 0.0);
        out[k].table.grid = grid;
        out[k].table.stored = stored[k];
    }
    parallel_for(na, threads, [&](std::size_t i) {
        const std::function<void(double, double*)> f = rows(fine.alphas[i]);
        std::vector<double> v(nv);
        for (std::size_t j = 0; j < nx; ++j) {
            f(fine.mu(i, static_cast<int>(j)), v.data());
            for (std::size_t k = 0; k < nv; ++k) {
                if (!std::isfinite(v[k]) || (stored[k] == Stored::log && !(v[k] > 0.0)))
                    throw std::runtime_error("albedo table: a value that is not finite" +
                                             std::string(stored[k] == Stored::log ? " and > 0" : "") + " at alpha " +
                                             format_shortest(fine.alphas[i]) + ": " + format_g17(v[k]));
                out[k].fine.values[i * nx + j] = v[k];
            }
        }
    });
    const auto r = static_cast<std::size_t>(refine);
    for (CheckedTable& t : out) {
        for (std::size_t i = 0; i < grid.alphas.size(); ++i)
            for (int j = 0; j < grid.n_x; ++j) {
                const double v = t.fine.at(i * r, static_cast<int>(j * r));
                t.table.values.push_back(t.table.stored == Stored::log ? std::log(v) : v);
            }
        for (std::size_t i = 0; i < na; ++i)
            for (std::size_t j = 0; j < nx; ++j) {
                const double alpha = fine.alphas[i], mu = fine.mu(i, static_cast<int>(j));
                const double e = std::abs(t.table.lookup(alpha, mu) - t.fine.values[i * nx + j]);
                InterpolationError& worst = mu < grazing_mu ? t.grazing : t.error;
                if (e > worst.max) worst = {e, alpha, mu};
            }
    }
    return out;
}

double lookup_power_law(const std::vector<double>& alphas, const std::vector<double>& values, double alpha,
                        const char* what) {
    require(alpha > 0.0 && std::isfinite(alpha), "alpha", "finite and > 0", alpha);
    require_one_value_each(alphas, values, what);
    return power_law_in_cell(alphas, values, alpha, cell(alphas, alpha).i, what);
}

double lookup_missing(const std::vector<double>& alphas, const std::vector<double>& missing, double alpha) {
    for (double m : missing) require(m > 0.0 && std::isfinite(m), "1 - E_avg", "finite and > 0", m);
    return lookup_power_law(alphas, missing, alpha, "1 - E_avg");
}

CheckedTable tabulate(const AlbedoGrid& grid, int refine, const AlbedoRow& row, unsigned threads) {
    return std::move(tabulate(
        grid, refine, {Stored::value},
        [&](double alpha) -> std::function<void(double, double*)> {
            std::function<double(double)> f = row(alpha);
            return [f = std::move(f)](double mu, double* out) { *out = f(mu); };
        },
        threads)[0]);
}

InterpolationError below_grid_error(const CheckedTable& t, const AlbedoRow& row, const std::vector<double>& factors,
                                    unsigned threads) {
    std::vector<InterpolationError> each(factors.size());
    parallel_for(factors.size(), threads, [&](std::size_t k) {
        require(factors[k] > 0.0 && factors[k] < 1.0, "a below-grid factor", "in (0, 1)", factors[k]);
        const double alpha = t.table.grid.alphas.front() * factors[k], c = t.table.grid.scale(alpha);
        const std::function<double(double)> f = row(alpha);
        for (int j = 0; j < t.fine.grid.n_x; ++j) {
            const double mu = t.fine.grid.mu_of(c, t.fine.grid.x(j));
            if (mu < grazing_mu) continue;
            const double e = std::abs(t.table.lookup(alpha, mu) - f(mu));
            if (e > each[k].max) each[k] = {e, alpha, mu};
        }
    });
    InterpolationError worst;
    for (const InterpolationError& e : each)
        if (e.max > worst.max) worst = e;
    return worst;
}

}  // namespace smithlab::compensation
