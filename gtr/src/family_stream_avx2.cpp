// The stream route of family_stream.hpp on AVX2 and FMA (GtrFamilyRoute::avx2), chosen at run time where the CPU has
// no AVX-512: sixteen points a block, four lanes at a time for the logs, the chart and the exps, and family.hpp's own
// polynomial (GtrFamily::polynomial) point by point on the leaf the stream's grid names. Built only where libmvec is
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

}  // namespace

// n: a multiple of 16. G1 as family.hpp's GtrFamily::G1_up, the same leaves, by the route of family_stream.hpp.
[[gnu::target("avx2,fma")]] void family_stream_avx2(const GtrFamilyStream& stream, const double* alpha,
                                                    const double* gamma, const double* mu, double* out, std::size_t n) {
    const GtrFamilyLeaf* leaves = gtr_family_data.leaves;
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
            for (std::size_t q = 0; q < sizeof(GtrFamilyLeaf) + 63; q += 64) _mm_prefetch(p + q, _MM_HINT_T0);
        }
        // 2. point by point: the leaf's coordinates and its polynomial (family.hpp's)
        for (int i = 0; i < block; ++i) {
            const GtrFamilyLeaf& l = leaves[id[i]];
            const std::array<double, 3> s = {(o.x[0][i] - l.centre[0]) * l.scale[0],
                                             (o.x[1][i] - l.centre[1]) * l.scale[1],
                                             (o.x[2][i] - l.centre[2]) * l.scale[2]};
            f[i] = GtrFamily::polynomial(l, s) + o.shift[i];
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
