// The GTR family evaluator for streams (family_stream.hpp): the leaves in lanes, the uniform grid of each top box
// (from family.hpp's k-d tree), the choice of route, and the checked call.
#include "smithlab/gtr/family_stream.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "smithlab/errors.hpp"
#include "smithlab/gtr/family.hpp"

namespace smithlab {

#if SMITHLAB_FAMILY_AVX512
void family_stream_avx512(const GtrFamilyStream& s, const double* alpha, const double* gamma, const double* mu,
                          double* out, std::size_t n);  // family_stream_avx512.cpp: n a multiple of 16
void family_stream_avx2(const GtrFamilyStream& s, const double* alpha, const double* gamma, const double* mu,
                        double* out, std::size_t n);  // family_stream_avx2.cpp: n a multiple of 16
#endif

const char* name(GtrFamilyRoute route) {
    switch (route) {
        case GtrFamilyRoute::avx2:
            return "AVX2";
        case GtrFamilyRoute::avx512:
            return "AVX-512";
        default:
            return "one point";
    }
}

namespace {

// The rows (i, j) of the terms of degree >= 2 (i + j <= degree; k from k0 = max(0, 2 - i - j) to degree - i - j):
// rows of length 5 (6 of them) and two of length 4 in group 0; the other two of length 4, the five of length 3 and one
// of 2 in group 1; five of length 2 and three of 1 in group 2; four of length 1 in group 3, and four zero lanes.
GtrFamilyStream::Lanes make_lanes() {
    static_assert(gtr_family_degree == 6, "the lanes are laid out for total degree 6");
    struct Row {
        int i, j, k0;
    };
    std::array<std::vector<Row>, 6> by_length;
    for (int i = 0; i <= gtr_family_degree; ++i)
        for (int j = 0; j <= gtr_family_degree - i; ++j) {
            const int k0 = std::max(0, 2 - i - j);
            by_length[gtr_family_degree - i - j - k0 + 1].push_back({i, j, k0});
        }
    GtrFamilyStream::Lanes L{};
    const std::array<std::array<int, 8>, 4> lengths = {
        {{5, 5, 5, 5, 5, 5, 4, 4}, {4, 4, 3, 3, 3, 3, 3, 2}, {2, 2, 2, 2, 2, 1, 1, 1}, {1, 1, 1, 1, 0, 0, 0, 0}}};
    for (int g = 0; g < 4; ++g) {
        for (int l = 0; l < 8; ++l) {
            Row r{7, 7, 7};  // a zero lane: its coefficients are 0, its factor any power (s^7)
            if (const int n = lengths[g][l]; n > 0) {
                r = by_length[n].front();
                by_length[n].erase(by_length[n].begin());
            }
            L.i[g][l] = r.i, L.j[g][l] = r.j, L.k0[g][l] = r.k0;
        }
    }
    return L;
}

// Each top box's leaves on a uniform grid at its finest split per axis: the k-d tree's splits are at the middle of
// their boxes, so each leaf is a block of the grid.
void fill_grid(const GtrFamilyData& d, int node, std::array<int, 3> lo, std::array<int, 3> hi,
               const GtrFamilyStream::Cell& cell, std::vector<std::uint16_t>& ids) {
    const GtrFamilyNode& n = d.nodes[node];
    if (n.next < 0) {
        for (int i = lo[0]; i < hi[0]; ++i)
            for (int j = lo[1]; j < hi[1]; ++j)
                for (int k = lo[2]; k < hi[2]; ++k)
                    ids[cell.offset + (((i << cell.depth[1]) + j) << cell.depth[2]) + k] =
                        static_cast<std::uint16_t>(~n.next);
        return;
    }
    const int middle = (lo[n.axis] + hi[n.axis]) / 2;
    std::array<int, 3> hi_low = hi, lo_high = lo;
    hi_low[n.axis] = lo_high[n.axis] = middle;
    fill_grid(d, n.next, lo, hi_low, cell, ids);
    fill_grid(d, n.next + 1, lo_high, hi, cell, ids);
}
void depths(const GtrFamilyData& d, int node, std::array<int, 3> here, std::array<int, 3>& most) {
    const GtrFamilyNode& n = d.nodes[node];
    if (n.next < 0) {
        for (int a = 0; a < 3; ++a) most[a] = std::max(most[a], here[a]);
        return;
    }
    ++here[n.axis];
    depths(d, n.next, here, most);
    depths(d, n.next + 1, here, most);
}

// A leaf's box and its constant and linear terms, the same in both layouts (Leaf, RowLeaf).
template <class L>
void copy_frame(const GtrFamilyLeaf& from, L& to) {
    for (int a = 0; a < 3; ++a)
        to.centre[a] = from.centre[a], to.scale[a] = from.scale[a], to.linear[a] = from.linear[a];
    to.c0 = from.c0;
}

// Each top box's finest split per axis; cells, the number of cells of all their grids (SIZE_MAX where a box's grid
// alone would pass 2^20)
std::vector<std::array<int, 3>> finest_splits(const GtrFamilyData& d, std::size_t& cells) {
    std::vector<std::array<int, 3>> most(2 * GtrFamily::top_cells);
    cells = 0;
    for (std::size_t top = 0; top < most.size(); ++top) {
        depths(d, static_cast<int>(top), {0, 0, 0}, most[top]);
        const int splits = most[top][0] + most[top][1] + most[top][2];
        if (splits > 20) cells = SIZE_MAX;
        else cells += std::size_t{1} << splits;
    }
    return most;
}

// The leaves in lanes (the last, empty, stays zero)
std::vector<GtrFamilyStream::Leaf> leaves_in_lanes(const GtrFamilyData& d, const GtrFamilyStream::Lanes& lanes) {
    using Lanes = GtrFamilyStream::Lanes;
    std::array<std::array<std::array<int, 7>, 7>, 7> where{};  // (i, j, k) -> index in GtrFamilyLeaf::higher
    for (int q = 0; q < GtrFamilyLeaf::n_higher; ++q) {
        const auto& t = gtr_family_plan.term[q];
        where[t[0]][t[1]][t[2]] = q;
    }
    std::vector<GtrFamilyStream::Leaf> leaves(d.n_leaves + 1);
    for (std::size_t n = 0; n < d.n_leaves; ++n) {
        const GtrFamilyLeaf& from = d.leaves[n];
        GtrFamilyStream::Leaf& to = leaves[n];
        copy_frame(from, to);
        for (int g = 0; g < 4; ++g)
            for (int t = 0; t < Lanes::steps[g]; ++t)
                for (int l = 0; l < 8; ++l) {
                    const int i = static_cast<int>(lanes.i[g][l]), j = static_cast<int>(lanes.j[g][l]);
                    const int k = static_cast<int>(lanes.k0[g][l]) + t;
                    to.c[Lanes::offset[g] + 8 * t + l] =
                        i + j + k <= gtr_family_degree ? from.higher[where[i][j][k]] : 0.0f;
                }
    }
    return leaves;
}

// The leaves by rows over k, for the AVX2 route (the last, empty, stays zero)
std::vector<GtrFamilyStream::RowLeaf> leaves_by_rows(const GtrFamilyData& d) {
    static_assert(gtr_family_degree == 6, "RowLeaf is laid out for total degree 6");
    std::vector<GtrFamilyStream::RowLeaf> leaves(d.n_leaves + 1);
    for (std::size_t n = 0; n < d.n_leaves; ++n) {
        const GtrFamilyLeaf& from = d.leaves[n];
        GtrFamilyStream::RowLeaf& to = leaves[n];
        copy_frame(from, to);
        for (int q = 0; q < GtrFamilyLeaf::n_higher; ++q) {
            const auto& t = gtr_family_plan.term[q];
            to.c[GtrFamilyStream::row_at(t[0], t[1]) + t[2]] = from.higher[q];
        }
    }
    return leaves;
}

bool cpu_has_avx512() {
#if SMITHLAB_FAMILY_AVX512
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
#else
    return false;
#endif
}
bool cpu_has_avx2() {
#if SMITHLAB_FAMILY_AVX512
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return false;
#endif
}

#if SMITHLAB_FAMILY_AVX512
// The stream's kernels take blocks of 16 points.
using Kernel = void (*)(const GtrFamilyStream&, const double*, const double*, const double*, double*, std::size_t);
constexpr std::size_t block = 16;

// out[i] for the whole blocks by the kernel, then the last few, padded with a point inside the domain; returns how
// many it wrote (all n)
std::size_t by_blocks(Kernel kernel, const GtrFamilyStream& s, const double* alpha, const double* gamma,
                      const double* mu, double* out, std::size_t n) {
    const std::size_t done = n - n % block;
    kernel(s, alpha, gamma, mu, out, done);
    if (done < n) {
        double a[block], g[block], m[block], o[block];
        for (std::size_t i = 0; i < block; ++i) {
            const bool in = done + i < n;
            a[i] = in ? alpha[done + i] : 1.0, g[i] = in ? gamma[done + i] : 2.0, m[i] = in ? mu[done + i] : 1.0;
        }
        kernel(s, a, g, m, o, block);
        std::copy(o, o + (n - done), out + done);
    }
    return n;
}
#endif

}  // namespace

const GtrFamilyStream& GtrFamilyStream::get() {
    static const GtrFamilyStream stream;
    return stream;
}

bool GtrFamilyStream::runs(GtrFamilyRoute route) const {
    return route == GtrFamilyRoute::one_point || (route == GtrFamilyRoute::avx2 && avx2_) ||
        (route == GtrFamilyRoute::avx512 && avx512_);
}

GtrFamilyStream::GtrFamilyStream() : lanes_(make_lanes()), avx2_(cpu_has_avx2()), avx512_(cpu_has_avx512()) {
    route_ = avx512_ ? GtrFamilyRoute::avx512 : avx2_ ? GtrFamilyRoute::avx2 : GtrFamilyRoute::one_point;
    if (!vectorized()) return;  // the stream is GtrFamily::G1_up point by point: nothing here is read
    const GtrFamilyData& d = gtr_family_data;
    // each top box's finest split per axis; the grid's leaf numbers are 16-bit, its cells counted in 32 bits
    std::size_t cells = 0;
    const std::vector<std::array<int, 3>> most = finest_splits(d, cells);
    if (d.n_leaves > 65535 || cells > (std::size_t{1} << 30)) {  // data this index cannot hold: one point at a time
        route_ = GtrFamilyRoute::one_point;
        avx2_ = avx512_ = false;
        return;
    }
    leaves_ = leaves_in_lanes(d, lanes_);
    if (avx2_) row_leaves_ = leaves_by_rows(d);
    // each top box's grid of leaf numbers
    ids_.reserve(cells + 1);
    for (std::size_t top = 0; top < most.size(); ++top) {
        const auto& m = most[top];
        const auto depth = [&](int a) { return static_cast<std::uint8_t>(m[a]); };
        const Cell cell{static_cast<std::int32_t>(ids_.size()), {depth(0), depth(1), depth(2)}, 0};
        cells_.push_back(cell);
        ids_.resize(ids_.size() + (std::size_t{1} << (m[0] + m[1] + m[2])));
        fill_grid(d, static_cast<int>(top), {0, 0, 0}, {1 << m[0], 1 << m[1], 1 << m[2]}, cell, ids_);
    }
    ids_.push_back(0);
}

void GtrFamilyStream::G1_up(GtrFamilyRoute route, const double* alpha, const double* gamma, const double* mu,
                            double* out, std::size_t n) const {
    std::size_t done = 0;
#if SMITHLAB_FAMILY_AVX512
    if (route == GtrFamilyRoute::avx512 && avx512_)
        done = by_blocks(family_stream_avx512, *this, alpha, gamma, mu, out, n);
    if (route == GtrFamilyRoute::avx2 && avx2_) done = by_blocks(family_stream_avx2, *this, alpha, gamma, mu, out, n);
#else
    (void)route;
#endif
    const GtrFamily& f = GtrFamily::get();
    for (std::size_t i = done; i < n; ++i) out[i] = f.G1_up(alpha[i], gamma[i], std::abs(mu[i]));
}

void G1_gtr_family(std::span<const double> alpha, std::span<const double> gamma, std::span<const double> mu,
                   std::span<double> out, std::size_t first) {
    const std::size_t n = out.size();
    if (alpha.size() != n || gamma.size() != n || mu.size() != n)
        throw input_error("family: alpha, gamma, mu and out must be of one length, got " +
                          std::to_string(alpha.size()) + ", " + std::to_string(gamma.size()) + ", " +
                          std::to_string(mu.size()) + " and " + std::to_string(n));
    // one pass with no branch on the data, then the first offending item, if any
    bool good = true;
    for (std::size_t i = 0; i < n; ++i)
        good &= GtrFamily::alpha_in_domain(alpha[i]) & GtrFamily::gamma_in_domain(gamma[i]) & !std::isnan(mu[i]);
    for (std::size_t i = 0; !good && i < n; ++i) {
        if (!GtrFamily::alpha_in_domain(alpha[i]) || !GtrFamily::gamma_in_domain(gamma[i]) || std::isnan(mu[i])) {
            auto item = [&](const char* name) { return std::string(name) + '[' + std::to_string(first + i) + ']'; };
            require(GtrFamily::alpha_in_domain(alpha[i]), item("family: alpha"), "in [1e-4, 1]", alpha[i]);
            require(GtrFamily::gamma_in_domain(gamma[i]), item("family: gamma"), "in [0, 20]", gamma[i]);
            throw input_error(item("family: mu") + " is NaN");
        }
    }
    GtrFamilyStream::get().G1_up(alpha.data(), gamma.data(), mu.data(), out.data(), n);
}

}  // namespace smithlab
