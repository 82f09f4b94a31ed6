// The stream route of family_stream.hpp on AVX2 and FMA (GtrFamilyRoute::avx2), chosen at run time where the CPU has
// no AVX-512: sixteen points a block, four lanes at a time for the logs, the chart and the exps, and point by point
// each leaf's polynomial on four lanes over the power of s2 (GtrFamilyStream::RowLeaf). Built only where libmvec is
// (glibc on x86-64); every function here carries its target, so the rest of smithlab stays baseline x86-64.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>

#include "smithlab/gtr/family.hpp"
#include "smithlab/gtr/family_stream.hpp"

// glibc's vector math (libmvec; the x86-64 vector function ABI's names for AVX2, 'd'): ln and exp on four doubles,
// within 4 ulp.
extern "C" __m256d _ZGVdN4v_log(__m256d);
extern "C" __m256d _ZGVdN4v_exp(__m256d);

namespace smithlab {

namespace {

constexpr int block = 16;

// Stage 1 of family_stream.hpp for four points: (ln alpha, gamma, z) in its chart, clamped to the chart's box (x),
// the box coordinates t = (x - lo) / step of the top grid, the chart, and the asymptotes' flag and shift.
struct Located4 {
    double x[3][block], t[3][block], below[block], shift[block];
    std::int64_t chart[block];
};
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void locate4(const double* alpha, const double* gamma,
                                                                    const double* mu, int h, Located4& o) {
    const __m256d half = _mm256_set1_pd(0.5), one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d a = _ZGVdN4v_log(_mm256_loadu_pd(alpha));
    const __m256d eta = _ZGVdN4v_log(_mm256_andnot_pd(sign, _mm256_loadu_pd(mu)));
    // GtrFamily::chart_of: chart 1 unless eta < a/2 (NaN: 1); z = xi = eta - a in chart 0, eta in chart 1
    const __m256d c1 = _mm256_cmp_pd(eta, _mm256_mul_pd(half, a), _CMP_NLT_UQ);
    const __m256d z = _mm256_blendv_pd(_mm256_sub_pd(eta, a), eta, c1);
    const __m256d coordinate[3] = {a, _mm256_loadu_pd(gamma), z};
    for (int d = 0; d < 3; ++d) {
        const __m256d lo =
            _mm256_blendv_pd(_mm256_set1_pd(GtrFamily::lo[0][d]), _mm256_set1_pd(GtrFamily::lo[1][d]), c1);
        const __m256d hi =
            _mm256_blendv_pd(_mm256_set1_pd(GtrFamily::hi[0][d]), _mm256_set1_pd(GtrFamily::hi[1][d]), c1);
        const __m256d inv =
            _mm256_blendv_pd(_mm256_set1_pd(GtrFamily::inv_step(0, d)), _mm256_set1_pd(GtrFamily::inv_step(1, d)), c1);
        // as GtrFamily::locate: x >= lo ? min(x, hi) : lo (NaN to lo)
        const __m256d above = _mm256_cmp_pd(coordinate[d], lo, _CMP_GE_OQ);
        const __m256d xc = _mm256_blendv_pd(lo, _mm256_min_pd(coordinate[d], hi), above);
        _mm256_storeu_pd(o.x[d] + h, xc);
        _mm256_storeu_pd(o.t[d] + h, _mm256_mul_pd(_mm256_sub_pd(xc, lo), inv));
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(o.chart + h), _mm256_srli_epi64(_mm256_castpd_si256(c1), 63));
    // family.hpp's asymptotes: below xi_lo in chart 0 (a flag), beyond eta_hi (slope -1 in ln mu: a shift
    // min(0, eta_hi - eta) of ln(mu Lambda))
    const __m256d low = _mm256_andnot_pd(c1, _mm256_cmp_pd(z, _mm256_set1_pd(GtrFamily::xi_lo), _CMP_LT_OQ));
    _mm256_storeu_pd(o.below + h, _mm256_and_pd(low, one));
    _mm256_storeu_pd(o.shift + h, _mm256_min_pd(zero, _mm256_sub_pd(_mm256_set1_pd(GtrFamily::eta_hi), eta)));
}

// The leaf of point i: its top box, then its cell in the box's grid (family_stream.hpp), as the AVX-512 route's
[[gnu::target("avx2,fma"), gnu::always_inline]] inline std::uint32_t leaf_of(const Located4& o, int i,
                                                                             const GtrFamilyStream::Cell* cells,
                                                                             const std::uint16_t* ids) {
    int top[3], cell = 0;
    for (int d = 0; d < 3; ++d) {
        top[d] = std::min(static_cast<int>(o.t[d][i]), GtrFamily::top[d] - 1);
        cell = cell * GtrFamily::top[d] + top[d];
    }
    const GtrFamilyStream::Cell& box = cells[o.chart[i] * static_cast<std::int64_t>(GtrFamily::top_cells) + cell];
    int fine = 0;
    for (int d = 0; d < 3; ++d) {
        const int n = 1 << box.depth[d];
        fine = (fine << box.depth[d]) + std::min(static_cast<int>((o.t[d][i] - top[d]) * n), n - 1);
    }
    return ids[box.offset + fine];
}

using RowLeaf = GtrFamilyStream::RowLeaf;
constexpr int degree = gtr_family_degree;

// Row (i, j)'s terms as doubles: k = 0..3 (lo), k = 4..7 (hi, where i + j <= 2)
template <int i, int j>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline __m256d row_lo(const float* c) {
    return _mm256_cvtps_pd(_mm_load_ps(c + GtrFamilyStream::row_at(i, j)));
}
template <int i, int j>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline __m256d row_hi(const float* c) {
    return _mm256_cvtps_pd(_mm_load_ps(c + GtrFamilyStream::row_at(i, j) + 4));
}
// Q_i = sum over j of s1^j row (i, j), as vectors over k (Horner in s1, from j = degree - i down to j)
template <int i, int j>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void in_s1(const float* c, __m256d s1, __m256d& lo,
                                                                  __m256d& hi) {
    if constexpr (j == degree - i) {
        lo = row_lo<i, j>(c);
    } else {
        in_s1<i, j + 1>(c, s1, lo, hi);
        lo = _mm256_fmadd_pd(lo, s1, row_lo<i, j>(c));
        if constexpr (i + j == 2) hi = row_hi<i, j>(c);
        if constexpr (i + j < 2) hi = _mm256_fmadd_pd(hi, s1, row_hi<i, j>(c));
    }
}
// R = sum over i of s0^i Q_i (Horner in s0, from i = degree down to i); the upper lanes from i = 2 down
template <int i>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void in_s0(const float* c, __m256d s0, __m256d s1, __m256d& lo,
                                                                  __m256d& hi) {
    __m256d q_lo, q_hi = _mm256_setzero_pd();
    in_s1<i, 0>(c, s1, q_lo, q_hi);
    if constexpr (i == degree) {
        lo = q_lo;
    } else {
        in_s0<i + 1>(c, s0, s1, lo, hi);
        lo = _mm256_fmadd_pd(lo, s0, q_lo);
        if constexpr (i == 2) hi = q_hi;
        if constexpr (i < 2) hi = _mm256_fmadd_pd(hi, s0, q_hi);
    }
}

// ln(mu Lambda) of one point: the leaf's constant and linear terms, and its others as R(k) summed against s2^k
[[gnu::target("avx2,fma"), gnu::always_inline]] inline double polynomial(const RowLeaf& leaf, const double s[3]) {
    __m256d lo, hi;
    in_s0<0>(leaf.c, _mm256_set1_pd(s[0]), _mm256_set1_pd(s[1]), lo, hi);
    const double z2 = s[2] * s[2];
    const __m256d powers = _mm256_set_pd(z2 * s[2], z2, s[2], 1.0);  // (1, s2, s2^2, s2^3)
    const __m256d r = _mm256_mul_pd(_mm256_fmadd_pd(hi, _mm256_set1_pd(z2 * z2), lo), powers);
    const __m128d h = _mm_add_pd(_mm256_castpd256_pd128(r), _mm256_extractf128_pd(r, 1));
    return (leaf.c0 + leaf.linear[0] * s[0]) + (leaf.linear[1] * s[1] + leaf.linear[2] * s[2]) +
        _mm_cvtsd_f64(_mm_add_sd(h, _mm_unpackhi_pd(h, h)));
}

}  // namespace

// n: a multiple of 16. G1 as family.hpp's GtrFamily::G1_up, the same leaves, by the route of family_stream.hpp.
[[gnu::target("avx2,fma")]] void family_stream_avx2(const GtrFamilyStream& stream, const double* alpha,
                                                    const double* gamma, const double* mu, double* out, std::size_t n) {
    const RowLeaf* leaves = stream.row_leaves().data();
    const GtrFamilyStream::Cell* cells = stream.cells().data();
    const std::uint16_t* ids = stream.ids().data();
    const double mu_lo_rel = GtrFamily::get().mu_lo_rel();
    const __m256d half = _mm256_set1_pd(0.5), one = _mm256_set1_pd(1.0), sign = _mm256_set1_pd(-0.0);
    Located4 o;
    alignas(32) double f[block];
    std::uint32_t id[block];
    for (std::size_t b = 0; b < n; b += block) {
        // 1. four at once: the chart and the coordinates; then each point's leaf, its lines prefetched
        for (int h = 0; h < block; h += 4) locate4(alpha + b + h, gamma + b + h, mu + b + h, h, o);
        for (int i = 0; i < block; ++i) {
            id[i] = leaf_of(o, i, cells, ids);
            const char* p = reinterpret_cast<const char*>(leaves + id[i]);
            for (std::size_t q = 0; q < sizeof(RowLeaf); q += 64) _mm_prefetch(p + q, _MM_HINT_T0);
        }
        // 2. point by point: the leaf's coordinates and its polynomial
        for (int i = 0; i < block; ++i) {
            const RowLeaf& l = leaves[id[i]];
            const double s[3] = {(o.x[0][i] - l.centre[0]) * l.scale[0], (o.x[1][i] - l.centre[1]) * l.scale[1],
                                 (o.x[2][i] - l.centre[2]) * l.scale[2]};
            f[i] = polynomial(l, s) + o.shift[i];
        }
        // 3. four at once: G1 = 1 / (1 - P/2 + (e^f + P alpha mu_lo / 2) / mu); mu = 0 gives 0, mu = inf 1
        for (int h = 0; h < block; h += 4) {
            const __m256d e = _ZGVdN4v_exp(_mm256_load_pd(f + h)), P = _mm256_loadu_pd(o.below + h);
            const __m256d k =
                _mm256_mul_pd(_mm256_mul_pd(P, _mm256_loadu_pd(alpha + b + h)), _mm256_set1_pd(0.5 * mu_lo_rel));
            const __m256d m = _mm256_andnot_pd(sign, _mm256_loadu_pd(mu + b + h));
            const __m256d Lambda = _mm256_sub_pd(_mm256_div_pd(_mm256_add_pd(e, k), m), _mm256_mul_pd(half, P));
            _mm256_storeu_pd(out + b + h, _mm256_div_pd(one, _mm256_add_pd(one, Lambda)));
        }
    }
}

}  // namespace smithlab
