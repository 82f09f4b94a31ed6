/// @file
/// smithlab/turn.hpp -- cos and sin of a fraction of a turn, 2 pi u for u in [0, 1): the uniform azimuth every
/// sampler draws, without libm's argument reduction (the walk draws one or two per bounce).
///
/// u from uniform01 is a multiple of 2^-53, so the reduction is exact: q = nearest integer to 4u, r = 4u - q in
/// [-1/2, 1/2] (both exact), x = r pi/2 in [-pi/4, pi/4] (pi/2 in two parts: half an ulp and a little), and (cos,
/// sin)(2 pi u) is (cos x, sin x) turned by q quarter turns. cos x and sin x are fdlibm's kernels (Sun Microsystems
/// 1993, k_cos.c and k_sin.c, __kernel_cos / __kernel_sin with a zero tail; their minimax polynomials on [-pi/4, pi/4]
/// are within 2^-58 of the functions): within an ulp or so, the accuracy of std::cos(2 pi u) itself.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

namespace smithlab {

/// cos and sin of one angle: c = cos, s = sin.
struct CosSin {
    /// The cosine c and the sine s.
    /// @{
    double c, s;
    /// @}
};

namespace detail {
/// fdlibm k_sin.c, y = 0: x + x^3 (S1 + x^2 (S2 + ... + x^2 S6)).
[[gnu::always_inline]] inline double kernel_sin(double x) {
    constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                     S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                     S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
    const double z = x * x, v = z * x, r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    return x + v * (S1 + z * r);
}
/// fdlibm k_cos.c, y = 0: 1 - x^2/2 + x^4 (C1 + ... + x^10 C6), with 1 - x^2/2 split as (1 - qx) - (x^2/2 - qx) above
/// |x| = 0.3 (qx = |x|/4 truncated to its high word, or 0.28125 above 0.78125) so that the subtraction keeps its
/// digits.
[[gnu::always_inline]] inline double kernel_cos(double x) {
    constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03, C3 = 2.48015872894767294178e-05,
                     C4 = -2.75573143513906633035e-07, C5 = 2.08757232129817482790e-09,
                     C6 = -1.13596475577881948265e-11;
    const double z = x * x, r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    const double ax = std::abs(x);
    if (ax < 0.3) return 1.0 - (0.5 * z - z * r);
    double qx = 0.28125;
    if (ax <= 0.78125) {
        const std::uint64_t high = (std::bit_cast<std::uint64_t>(ax) >> 32) - 0x00200000u;  // |x| / 4, high word
        qx = std::bit_cast<double>(high << 32);
    }
    const double hz = 0.5 * z - qx, a = 1.0 - qx;
    return a - (hz - z * r);
}
}  // namespace detail

/// (cos 2 pi u, sin 2 pi u) for u in [0, 1) (any finite u that is a multiple of 2^-53 reduces exactly; others to the
/// rounding of 4u). Always inlined: a call would spill the sampler's registers around 30 flops.
[[gnu::always_inline]] inline CosSin cos_sin_turn(double u) {
    constexpr double pio2_hi = 1.57079632679489655800e+00, pio2_lo = 6.12323399573676603587e-17;  // fdlibm's
    constexpr double round = 0x1.8p52;  // t + round - round: t rounded to the nearest integer, |t| < 2^51
    const double t = 4.0 * u, q = (t + round) - round, r = t - q;
    const double x = r * pio2_hi + r * pio2_lo;
    const double c = detail::kernel_cos(x), s = detail::kernel_sin(x);
    const auto k = static_cast<std::int64_t>(q);
    // (cos, sin)(x + k pi/2): k = 1 gives (-s, c), k = 2 (-c, -s), k = 3 (s, -c).
    const bool odd = (k & 1) != 0;
    const double sign = (k & 2) != 0 ? -1.0 : 1.0;
    return {sign * (odd ? -s : c), sign * (odd ? c : s)};
}

}  // namespace smithlab
