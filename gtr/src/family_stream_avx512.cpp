// The stream route of family_stream.hpp on AVX-512 (F and VL), chosen at run time (GtrFamilyStream::vectorized):
// sixteen points a block, eight lanes at a time. Built only where libmvec is (glibc on x86-64); every function here
// carries its target, so the rest of smithlab stays baseline x86-64.
#include <immintrin.h>

#include <cstdint>

#include "smithlab/gtr/family.hpp"
#include "smithlab/gtr/family_stream.hpp"

// glibc's vector math (libmvec; its names are the x86-64 vector function ABI's, which glibc's own headers declare
// only under -ffast-math): ln and exp on eight doubles, within 4 ulp.
extern "C" __m512d _ZGVeN8v_log(__m512d);
extern "C" __m512d _ZGVeN8v_exp(__m512d);

namespace smithlab {

namespace {

// (1, x, x^2, ..., x^7)
[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline __m512d powers(double x) {
    const __m512d X = _mm512_set1_pd(x), one = _mm512_set1_pd(1.0);
    const __m512d x2 = _mm512_mul_pd(X, X), x4 = _mm512_mul_pd(x2, x2);
    const __m512d a = _mm512_mask_blend_pd(0xAA, one, X), b = _mm512_mask_blend_pd(0xCC, one, x2);
    return _mm512_mul_pd(_mm512_mul_pd(a, b), _mm512_mask_blend_pd(0xF0, one, x4));
}

[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline __m512d terms(const float* c) {
    return _mm512_cvtps_pd(_mm256_loadu_ps(c));
}

struct LaneIndex {
    __m512i i[4], j[4], k0[4];
};

// ln(mu Lambda) of one point: the leaf's constant and linear terms, and its 80 others on eight lanes
// (family_stream.hpp; Horner in s2 for each group's rows, times each row's s0^i s1^j s2^k0, summed over the lanes).
[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline double polynomial(
    const GtrFamilyStream::Leaf& leaf, const double s[3], const LaneIndex& L) {
    const __m512d P0 = powers(s[0]), P1 = powers(s[1]), P2 = powers(s[2]), s2 = _mm512_set1_pd(s[2]);
    __m512d factor[4];
    for (int g = 0; g < 4; ++g)
        factor[g] = _mm512_mul_pd(_mm512_mul_pd(_mm512_permutexvar_pd(L.i[g], P0), _mm512_permutexvar_pd(L.j[g], P1)),
                                  _mm512_permutexvar_pd(L.k0[g], P2));
    using Lanes = GtrFamilyStream::Lanes;
    __m512d h[4];
    for (int g = 0; g < 4; ++g) {
        const float* c = leaf.c + Lanes::offset[g];
        h[g] = terms(c + 8 * (Lanes::steps[g] - 1));
        for (int t = Lanes::steps[g] - 2; t >= 0; --t) h[g] = _mm512_fmadd_pd(h[g], s2, terms(c + 8 * t));
    }
    const __m512d sum = _mm512_add_pd(_mm512_fmadd_pd(h[0], factor[0], _mm512_mul_pd(h[1], factor[1])),
                                      _mm512_fmadd_pd(h[2], factor[2], _mm512_mul_pd(h[3], factor[3])));
    return (leaf.c0 + leaf.linear[0] * s[0]) + (leaf.linear[1] * s[1] + leaf.linear[2] * s[2]) +
        _mm512_reduce_add_pd(sum);
}

constexpr int block = 16;

// A block's points between the steps: the coordinates clamped to their chart's box, the leaf numbers, the
// asymptotes' flag and shift, and ln(mu Lambda).
struct Block {
    alignas(64) double x[3][block];
    alignas(64) double shift[block];
    alignas(64) double below[block];
    alignas(64) double f[block];
    alignas(64) std::int32_t id[block];
};

[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline LaneIndex load_lanes(
    const GtrFamilyStream::Lanes& lanes) {
    LaneIndex L;
    for (int g = 0; g < 4; ++g) {
        L.i[g] = _mm512_loadu_si512(lanes.i[g]);
        L.j[g] = _mm512_loadu_si512(lanes.j[g]);
        L.k0[g] = _mm512_loadu_si512(lanes.k0[g]);
    }
    return L;
}

// The coordinates clamped to their chart's box (chart 1 where c1) into x[d] + h; t[d], the position in units of the
// chart's top boxes, and top[d], the top box.
[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline void clamp_to_box(const __m512d coordinate[3],
                                                                                          __mmask8 c1, Block& work,
                                                                                          int h, __m512d t[3],
                                                                                          __m256i top[3]) {
    for (int d = 0; d < 3; ++d) {
        const __m512d lo =
            _mm512_mask_blend_pd(c1, _mm512_set1_pd(GtrFamily::lo[0][d]), _mm512_set1_pd(GtrFamily::lo[1][d]));
        const __m512d hi =
            _mm512_mask_blend_pd(c1, _mm512_set1_pd(GtrFamily::hi[0][d]), _mm512_set1_pd(GtrFamily::hi[1][d]));
        const __m512d inv = _mm512_mask_blend_pd(c1, _mm512_set1_pd(GtrFamily::inv_step(0, d)),
                                                 _mm512_set1_pd(GtrFamily::inv_step(1, d)));
        // as GtrFamily::locate: x >= lo ? min(x, hi) : lo (NaN to lo)
        const __mmask8 above = _mm512_cmp_pd_mask(coordinate[d], lo, _CMP_GE_OQ);
        const __m512d xc = _mm512_mask_blend_pd(above, lo, _mm512_min_pd(coordinate[d], hi));
        _mm512_store_pd(work.x[d] + h, xc);
        t[d] = _mm512_mul_pd(_mm512_sub_pd(xc, lo), inv);
        top[d] = _mm256_min_epi32(_mm512_cvttpd_epi32(t[d]), _mm256_set1_epi32(GtrFamily::top[d] - 1));
    }
}

// The leaf numbers of eight points: their top box (chart 1's after chart 0's), the cell of the box's grid at its
// finest split per axis (Cell: offset, then depth[3] bytes), the 16-bit number there, read 32 bits at a time (ids
// ends in a spare zero).
[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline __m256i leaf_numbers(
    const __m512d t[3], const __m256i top[3], __mmask8 c1, const long long* cells, const int* ids) {
    __m256i cell = _mm256_add_epi32(
        _mm256_mullo_epi32(_mm256_add_epi32(_mm256_mullo_epi32(top[0], _mm256_set1_epi32(GtrFamily::top[1])), top[1]),
                           _mm256_set1_epi32(GtrFamily::top[2])),
        top[2]);
    cell = _mm256_mask_add_epi32(cell, c1, cell, _mm256_set1_epi32(static_cast<int>(GtrFamily::top_cells)));
    const __m512i box = _mm512_i32gather_epi64(cell, cells, 8);
    const __m256i offset = _mm512_cvtepi64_epi32(box);
    const __m256i depth = _mm512_cvtepi64_epi32(_mm512_srli_epi64(box, 32));
    __m256i fine = _mm256_setzero_si256();
    for (int d = 0; d < 3; ++d) {
        const __m256i k = _mm256_and_si256(_mm256_srli_epi32(depth, 8 * d), _mm256_set1_epi32(0xFF));
        const __m256i cells_d = _mm256_sllv_epi32(_mm256_set1_epi32(1), k);
        const __m512d in_box = _mm512_sub_pd(t[d], _mm512_cvtepi32_pd(top[d]));
        const __m256i j = _mm256_min_epi32(_mm512_cvttpd_epi32(_mm512_mul_pd(in_box, _mm512_cvtepi32_pd(cells_d))),
                                           _mm256_sub_epi32(cells_d, _mm256_set1_epi32(1)));
        fine = _mm256_add_epi32(_mm256_sllv_epi32(fine, k), j);
    }
    return _mm256_and_si256(_mm256_i32gather_epi32(ids, _mm256_add_epi32(offset, fine), 2), _mm256_set1_epi32(0xFFFF));
}

// Step 1 for points h .. h + 7 of the block (alpha, gamma, mu at them): (ln alpha, gamma, z) in its chart, clamped
// to the chart's box; the leaf; the asymptotes' flag and shift.
[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline void locate8(
    const double* alpha, const double* gamma, const double* mu, const long long* cells, const int* ids, Block& work,
    int h) {
    const __m512d a = _ZGVeN8v_log(_mm512_loadu_pd(alpha));
    const __m512d eta = _ZGVeN8v_log(_mm512_abs_pd(_mm512_loadu_pd(mu)));
    // GtrFamily::chart_of: chart 1 unless eta < a/2 (NaN: 1); z = xi = eta - a in chart 0, eta in chart 1
    const __mmask8 c1 = _mm512_cmp_pd_mask(eta, _mm512_mul_pd(_mm512_set1_pd(0.5), a), _CMP_NLT_UQ);
    const __m512d z = _mm512_mask_sub_pd(eta, static_cast<__mmask8>(~c1), eta, a);
    const __m512d coordinate[3] = {a, _mm512_loadu_pd(gamma), z};
    __m512d t[3];
    __m256i top[3];
    clamp_to_box(coordinate, c1, work, h, t, top);
    _mm256_store_si256(reinterpret_cast<__m256i*>(work.id + h), leaf_numbers(t, top, c1, cells, ids));
    // family.hpp's asymptotes: below xi_lo in chart 0 (a flag), beyond eta_hi (slope -1 in ln mu: a shift
    // min(0, eta_hi - eta) of ln(mu Lambda))
    const __mmask8 low = _mm512_kandn(c1, _mm512_cmp_pd_mask(z, _mm512_set1_pd(GtrFamily::xi_lo), _CMP_LT_OQ));
    _mm512_store_pd(work.below + h, _mm512_maskz_mov_pd(low, _mm512_set1_pd(1.0)));
    _mm512_store_pd(work.shift + h,
                    _mm512_min_pd(_mm512_setzero_pd(), _mm512_sub_pd(_mm512_set1_pd(GtrFamily::eta_hi), eta)));
}

// Step 2, point by point: the leaf's coordinates and its polynomial, after a prefetch of the block's leaves.
[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline void leaf_polynomials(
    const GtrFamilyStream::Leaf* leaves, const LaneIndex& L, Block& work) {
    for (int i = 0; i < block; ++i) {
        const char* p = reinterpret_cast<const char*>(leaves + work.id[i]);
        for (std::size_t q = 0; q < sizeof(GtrFamilyStream::Leaf); q += 64) _mm_prefetch(p + q, _MM_HINT_T0);
    }
    for (int i = 0; i < block; ++i) {
        const GtrFamilyStream::Leaf& l = leaves[work.id[i]];
        const double s[3] = {(work.x[0][i] - l.centre[0]) * l.scale[0], (work.x[1][i] - l.centre[1]) * l.scale[1],
                             (work.x[2][i] - l.centre[2]) * l.scale[2]};
        work.f[i] = polynomial(l, s, L) + work.shift[i];
    }
}

// Step 3 for points h .. h + 7 of the block: G1 = 1 / (1 - P/2 + (e^f + P alpha mu_lo / 2) / mu); mu = 0 gives 0,
// mu = inf 1
[[gnu::target("avx512f,avx512vl,avx2,fma"), gnu::always_inline]] inline void G1_of8(const double* alpha,
                                                                                    const double* mu, const Block& work,
                                                                                    int h, double mu_lo_rel,
                                                                                    double* out) {
    const __m512d half = _mm512_set1_pd(0.5), one = _mm512_set1_pd(1.0);
    const __m512d e = _ZGVeN8v_exp(_mm512_load_pd(work.f + h)), P = _mm512_load_pd(work.below + h);
    const __m512d k = _mm512_mul_pd(_mm512_mul_pd(P, _mm512_loadu_pd(alpha)), _mm512_set1_pd(0.5 * mu_lo_rel));
    const __m512d m = _mm512_abs_pd(_mm512_loadu_pd(mu));
    const __m512d Lambda = _mm512_sub_pd(_mm512_div_pd(_mm512_add_pd(e, k), m), _mm512_mul_pd(half, P));
    _mm512_storeu_pd(out, _mm512_div_pd(one, _mm512_add_pd(one, Lambda)));
}

}  // namespace

// n: a multiple of 16. G1 as family.hpp's GtrFamily::G1_up, the same leaves, by the route of family_stream.hpp.
[[gnu::target("avx512f,avx512vl,avx2,fma")]] void family_stream_avx512(const GtrFamilyStream& stream,
                                                                       const double* alpha, const double* gamma,
                                                                       const double* mu, double* out, std::size_t n) {
    const LaneIndex L = load_lanes(stream.lanes());
    const GtrFamilyStream::Leaf* leaves = stream.leaves().data();
    const long long* cells = reinterpret_cast<const long long*>(stream.cells().data());
    const int* ids = reinterpret_cast<const int*>(stream.ids().data());
    const double mu_lo_rel = GtrFamily::get().mu_lo_rel();
    Block work;
    for (std::size_t b = 0; b < n; b += block) {
        // 1. eight at once: where the points are, their leaves
        for (int h = 0; h < block; h += 8) locate8(alpha + b + h, gamma + b + h, mu + b + h, cells, ids, work, h);
        // 2. point by point: the polynomials
        leaf_polynomials(leaves, L, work);
        // 3. eight at once: G1
        for (int h = 0; h < block; h += 8) G1_of8(alpha + b + h, mu + b + h, work, h, mu_lo_rel, out + b + h);
    }
}

}  // namespace smithlab
