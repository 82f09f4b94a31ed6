#include "smithlab/compensation/scattering_orders.hpp"

#include <algorithm>
#include <cmath>

#include "smithlab/errors.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::compensation {

OrderEstimate scattering_orders(const walk::AlbedoTally& mirror) {
    require(mirror.walks > 0, "the order tally's walks", "> 0", static_cast<double>(mirror.walks));
    require(mirror.capped == 0, "the order tally's capped walks", "0 (mirror facets always leave)",
            static_cast<double>(mirror.capped));
    // n_k: the walks leaving after k hits (bins 1, 2, 3, 4+), each of weight 1.
    double n[walk::order_bins];
    double first_three = 0.0, escaped = 0.0;  // every walk's hits up to its third; the walks that left
    for (int o = 0; o < walk::order_bins; ++o) {
        walk::Moments m;
        for (int h = 0; h < 2; ++h)
            for (int c = 0; c < 2; ++c) m.merge(mirror.bins[walk::AlbedoTally::index(h, o, c)]);
        if (m.sum != m.sum2)
            throw input_error("scattering orders: a walk left with a weight other than 1 (not mirror facets)");
        n[o] = m.sum;
        escaped += m.sum;
        first_three += std::min(o + 1, 3) * m.sum;
    }
    if (escaped != static_cast<double>(mirror.walks))
        throw input_error("scattering orders: a walk did not leave (not mirror facets)");
    OrderEstimate e;
    const double multiple = n[1] + n[2] + n[3];
    e.multiple = static_cast<std::int64_t>(multiple);
    if (multiple == 0.0) return e;
    e.orders.q2 = n[1] / multiple;
    e.orders.q3 = n[2] / multiple;
    // p = n_4+ over the hits past the third (events counts every hit of every walk).
    e.orders.p = n[3] > 0.0 ? n[3] / (static_cast<double>(mirror.events) - first_three) : 1.0;
    e.q2_stderr = std::sqrt(e.orders.q2 * (1.0 - e.orders.q2) / multiple);
    e.q3_stderr = std::sqrt(e.orders.q3 * (1.0 - e.orders.q3) / multiple);
    return e;
}

double multiple_scattering_albedo(double E, const ScatteringOrders& q, double F_avg) {
    require(E >= 0.0 && E <= 1.0 + 1e-12, "E(mu)", "in [0, 1] (within a rounding)", E);
    require(F_avg >= 0.0 && F_avg <= 1.0, "F_avg", "in [0, 1]", F_avg);
    require(q.p > 0.0 && q.p <= 1.0, "the tail's escape chance p", "in (0, 1]", q.p);
    require(q.q1 >= 0.0 && q.q1 <= 1.0, "the single-scattering share q_1", "in [0, 1]", q.q1);
    const double F = F_avg, F2 = F * F;
    const double tail = (1.0 - q.q2 - q.q3) * F2 * F2 * q.p / (1.0 - F * (1.0 - q.p));
    return std::max(0.0, 1.0 - E) * (q.q1 * F + (1.0 - q.q1) * (F2 * q.q2 + F2 * F * q.q3 + tail));
}

ScatteringOrders OrderTables::lookup(double alpha, double mu) const {
    return {q2.lookup(alpha, mu), q3.lookup(alpha, mu), p.lookup(alpha, mu),
            q1.values.empty() ? 0.0 : q1.lookup(alpha, mu)};
}

OrderTables tabulate_orders(const AlbedoGrid& grid, const OrderCell& trace, unsigned threads) {
    grid.check();
    const std::size_t nx = static_cast<std::size_t>(grid.n_x), nodes = grid.alphas.size() * nx;
    OrderTables t;
    for (AlbedoTable* table : {&t.q2, &t.q3, &t.p}) {
        table->grid = grid;
        table->values.assign(nodes, 0.0);
    }
    t.q2_stderr.assign(nodes, 0.0);
    t.q3_stderr.assign(nodes, 0.0);
    util::reduce_blocks(
        nodes, threads, 0,
        [&](std::uint64_t k) {
            const std::size_t i = k / nx;
            const int j = static_cast<int>(k % nx);
            const double mu = std::max(grid.mu(i, j), grazing_mu);  // a walk cannot start horizontal
            const OrderEstimate e = scattering_orders(trace(k, grid.alphas[i], mu));
            t.q2.values[k] = e.orders.q2;
            t.q3.values[k] = e.orders.q3;
            t.p.values[k] = e.orders.p;
            t.q2_stderr[k] = e.q2_stderr;
            t.q3_stderr[k] = e.q3_stderr;
            return 0;
        },
        [](int&, int) {}, [](std::uint64_t) {});
    return t;
}

}  // namespace smithlab::compensation
