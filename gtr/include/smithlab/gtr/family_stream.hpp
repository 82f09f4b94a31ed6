/// @file
/// smithlab/gtr/family_stream.hpp -- G1 of GTR for a stream of (alpha, gamma, mu) points: the family evaluator of
/// family.hpp, eight or four points at a time (<= 30 ns a G1 on random streams; one call of
/// GtrFamily::G1_up is ~62 ns, a chain of dependent steps that a core cannot overlap with the next call's).
///
/// Same leaves and the same stated bounds as GtrFamily (error_bound(), G1_error_bound()); what differs is the route
/// through them, so the two agree to rounding (1e-12 relative in Lambda, tests/test_family.cpp), not bit for bit, but
/// for points within a few ulps of a box's edge (the charts' boundary included), where the two may pick neighbouring
/// leaves, both of which hold there:
///   1. eight points at once (AVX-512): ln alpha and ln mu (glibc's libmvec), the chart, each top box's leaves on a
///      uniform grid at its finest split (built here from the k-d tree: no descent, no branch on the data), the
///      asymptotes by min and a masked move;
///   2. point by point: the leaf's box coordinates s and its polynomial, its 80 float terms laid out by rows of one
///      length side by side on eight lanes (a copy of family.hpp's leaves in that order; Horner in s2 on all lanes at
///      once, each lane's s0^i s1^j s2^k0 from three permutes of the powers; the leaves are prefetched first);
///   3. eight at once again: the exp and G1 = 1 / (1 - P/2 + (e^f + P alpha mu_lo / 2) / mu), P = 1 below xi_lo
///      (family.hpp's lower asymptote), else 0.
/// On AVX2 and FMA without AVX-512 (GtrFamilyRoute::avx2): stages 1 and 3 four lanes at a time (libmvec's 4-lane logs
/// and exps), the same grids; in stage 2 each leaf's polynomial with the four lanes over the power k of s2: its terms
/// as a vector over k for each row (i, j) (RowLeaf), Horner in s1 within each i, then in s0, all FMA on four-lane
/// vectors, then the dot product with (1, s2, s2^2, s2^3) plus s2^4 times the upper lanes; the leaves are prefetched
/// first. The same G1 as the one call to rounding (tests/test_family_avx2.cpp runs this route by name).
/// Built at first use from the compiled-in data (tens of ms; 3.4 MB of leaves in the eight-lane layout, 4.3 MB more in
/// RowLeaf's where the AVX2 route runs, 47 kB of index), shared by every thread. The route is chosen at run time by
/// CPU detection, AVX-512 (F and VL) first, then AVX2 and FMA; where the CPU has neither, or the build has no libmvec
/// (glibc's, x86-64), the stream is GtrFamily::G1_up point by point, and none of this is built: the same values, at
/// the one-call speed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace smithlab {

/// The routes of GtrFamilyStream::G1_up: point by point (GtrFamily::G1_up), four lanes (AVX2 and FMA), eight lanes
/// (AVX-512 F and VL).
enum class GtrFamilyRoute { one_point, avx2, avx512 };
const char* name(GtrFamilyRoute route);  ///< "one point", "AVX2", "AVX-512"

/// G1(alpha[i], gamma[i], |mu[i]|) into out[i] for every i: the checked stream call. Everything is checked before
/// anything is written: input_error for spans of different lengths, and naming the first offending item otherwise
/// ("family: alpha[3] must be in [1e-4, 1], got 0"; gamma as for alpha, in [0, 20]; "mu[7] is NaN"), counted from
/// `first` (a caller streaming a long array in parts names the item by its place in the whole). mu = 0 gives 0,
/// |mu| = inf gives 1, as everywhere (smith.hpp).
void G1_gtr_family(std::span<const double> alpha, std::span<const double> gamma, std::span<const double> mu,
                   std::span<double> out, std::size_t first = 0);

/// G1 of GtrFamily at many points at once, on the fastest vector route this CPU and build run (the file comment); one
/// instance, built at first use.
class GtrFamilyStream {
public:
    /// The stream, built at the first call (thread-safe) and shared.
    static const GtrFamilyStream& get();

    /// G1 at n points (alpha[i], gamma[i], |mu[i]|), alpha in [1e-4, 1], gamma in [0, 20]: nothing is checked (a NaN
    /// gives some value, never a read out of bounds). out may be any of the inputs (in place). No allocation,
    /// exception or virtual call.
    void G1_up(const double* alpha, const double* gamma, const double* mu, double* out, std::size_t n) const {
        G1_up(route_, alpha, gamma, mu, out, n);
    }
    /// The same on a given route: one this CPU and build run (runs(route)), else point by point. The routes agree to
    /// rounding (as the stream and the one call do, above).
    void G1_up(GtrFamilyRoute route, const double* alpha, const double* gamma, const double* mu, double* out,
               std::size_t n) const;
    /// The route G1_up takes here: the fastest this CPU and build run.
    GtrFamilyRoute route() const { return route_; }
    /// Whether this CPU and build run `route` (one_point always).
    bool runs(GtrFamilyRoute route) const;
    /// Whether G1_up runs several points at a time here (else it is GtrFamily::G1_up point by point).
    bool vectorized() const { return route_ != GtrFamilyRoute::one_point; }

    /// The layout G1_up's vector routes read (family_stream.cpp builds it; family_stream_avx512.cpp reads Leaf,
    /// family_stream_avx2.cpp RowLeaf, both the grids).
    /// One leaf: its 80 terms of degree >= 2 on eight lanes, lane l of group g holding row (i, j) = lanes[g][l]:
    /// group 0 five Horner steps in s2, group 1 four, group 2 two, group 3 one (96 floats, zero where a row is
    /// shorter), then the box and the constant and linear terms (as GtrFamilyLeaf).
    struct alignas(64) Leaf {
        /// The 80 terms of degree >= 2 in the lanes' order (96 floats, zeros where a row is shorter).
        float c[96];
        /// The box (s = (x - centre) * scale) and the constant and linear terms.
        /// @{
        double centre[3], scale[3], c0, linear[3];
        /// @}
    };
    static_assert(sizeof(Leaf) == 512);  // eight cache lines, prefetched whole
    /// One top box: where its grid of leaf numbers starts in `ids`, and its finest split per axis (2^depth cells).
    struct Cell {
        /// Where the box's grid of leaf numbers starts in `ids`.
        std::int32_t offset;
        /// The box's finest split per axis (2^depth cells), and a byte of padding.
        /// @{
        std::uint8_t depth[3], pad;
        /// @}
    };
    /// Which row (i, j) and first power k0 of s2 each of the eight lanes of each group holds.
    struct Lanes {
        static constexpr int steps[4] = {5, 4, 2, 1};      ///< Horner steps of each group
        static constexpr int offset[4] = {0, 40, 72, 88};  ///< where each group's 8 x steps floats start in Leaf::c
        /// @{
        std::int64_t i[4][8], j[4][8], k0[4][8];  ///< row (i, j) of each lane and its first power of s2; 7: a zero lane
        /// @}
    };
    static_assert(Lanes::offset[3] + 8 * Lanes::steps[3] == 96);
    /// The AVX2 route's leaves: the box and the constant and linear terms (as GtrFamilyLeaf), then for each row
    /// (i, j), in (i, j) order from row_at, its c_ijk as a vector over k: k = 0..7 where i + j <= 2, else k = 0..3
    /// (i + j + k <= degree), zero where k < k0 or i + j + k > degree (136 floats; ten cache lines).
    struct alignas(64) RowLeaf {
        /// The box (s = (x - centre) * scale) and the constant and linear terms.
        /// @{
        double centre[3], scale[3], c0, linear[3];
        /// @}
        /// Each row's c_ijk as a vector over k, in (i, j) order (row_at).
        float c[136];
    };
    static_assert(sizeof(RowLeaf) == 640);
    /// where row (i, j)'s vector starts in RowLeaf::c
    static constexpr int row_at(int i, int j) {
        int at = 0;
        for (int a = 0; a <= i; ++a)
            for (int b = 0; b <= 6 - a && (a < i || b < j); ++b) at += a + b <= 2 ? 8 : 4;
        return at;
    }
    /// The leaves in each layout (row_leaves: empty where the AVX2 route does not run), the top boxes, and the lanes'
    /// plan.
    /// @{
    const std::vector<RowLeaf>& row_leaves() const { return row_leaves_; }
    const std::vector<Leaf>& leaves() const { return leaves_; }
    const std::vector<Cell>& cells() const { return cells_; }
    /// @}
    const std::vector<std::uint16_t>& ids() const { return ids_; }  ///< one past the last is a zero (32-bit gathers)
    /// The lanes' plan of Leaf::c.
    const Lanes& lanes() const { return lanes_; }

private:
    GtrFamilyStream();
    std::vector<Leaf> leaves_;
    std::vector<RowLeaf> row_leaves_;  ///< built where the AVX2 route runs
    std::vector<Cell> cells_;
    std::vector<std::uint16_t> ids_;
    Lanes lanes_{};
    GtrFamilyRoute route_ = GtrFamilyRoute::one_point;
    bool avx2_ = false, avx512_ = false;  ///< what this CPU and build run
};
static_assert(GtrFamilyStream::row_at(6, 0) + 4 == 136);  // every row placed, the last of four floats

}  // namespace smithlab
