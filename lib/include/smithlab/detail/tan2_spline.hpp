/// @file
/// smithlab/detail/tan2_spline.hpp -- a function of t = tan^2(theta) > 0 at the cost of a cubic, indexed by the bits of
/// t: no log, exp or root. What the walk calls for Lambda of an NDF without GGX's closed form (fast_lambda.hpp).
///
/// A double's bits, read as an integer, are piecewise linear in its value: within a binade [2^e, 2^(e+1)) the 52
/// mantissa bits are (t / 2^e - 1) 2^52. Their top sub_bits bits and the exponent pick one of 2^sub_bits equal pieces
/// of the binade (a relative width of at most 2^-sub_bits, so every decade of t is covered alike, as a table in ln t
/// would be, without its log), and the remaining 48 bits are the position u in [0, 1) within the piece, exactly. Each
/// piece holds the cubic in u through the function's values at u = 0, 1/3, 2/3, 1 (Lagrange) or, where that misses, the
/// cubic through the logs of those values, exponentiated (a function falling off exponentially, Beckmann's Lambda
/// ~ e^(-1 / (alpha^2 t)) at small t, is smooth in log). A piece answers where its cubic meets the function within
/// tolerance/2 max(|f|, floor) (relative above the floor, absolute below it) at u = 1/2 and 1/2 +- sqrt(5)/6, where the
/// node polynomial peaks (its error, led by the fourth derivative, peaks there too); any other piece
/// answers NaN, as does any t outside [2^lowest_binade, 2^highest_binade): the caller evaluates the function itself
/// there. For f ~ C t^p the relative error
/// of a piece is about |p (p - 1) (p - 2) (p - 3)| 2^-16 / 2000 (the node polynomial's 0.0123 over 4!): 7e-9 for
/// p = 1/2, Lambda's grazing limit, 0 for p = 1, its limit at normal incidence for tails like GGX's; pieces fail where
/// Lambda falls off exponentially (Beckmann's e^(-1 / (alpha^2 t)) at small t).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace smithlab::detail {

/// A function of t = tan^2(theta) > 0 tabulated as cubics indexed by the bits of t (the file comment).
class Tan2Spline {
public:
    /// Each binade of t is split in 2^sub_bits equal pieces.
    static constexpr int sub_bits = 4;
    /// @{
    static constexpr int lowest_binade = -40, highest_binade = 40;  ///< tan(theta) in [2^-20, 2^20)
    /// @}

    /// f(t) >= 0 at every t the table covers (finite where a piece is to answer).
    Tan2Spline(const std::function<double(double)>& f, double tolerance, double floor);

    /// f(t), or NaN where the table does not answer.
    double operator()(double t) const {
        const std::uint64_t bits = std::bit_cast<std::uint64_t>(t);
        const std::uint64_t piece = (bits >> shift) - first_;
        if (piece >= coef_.size()) return std::numeric_limits<double>::quiet_NaN();  // outside, negative, NaN
        const double u = static_cast<double>(bits & low_mask) * 0x1p-48;
        const std::array<double, 4>& c = coef_[piece];
        const double p = ((c[3] * u + c[2]) * u + c[1]) * u + c[0];  // NaN where the piece does not answer
        return in_log_[piece] ? std::exp(p) : std::max(p, 0.0);      // a cubic near 0 within the floor may dip below it
    }

    /// The tolerance and the floor it was built to: a piece answers within tolerance/2 max(|f|, floor).
    /// @{
    double tolerance() const { return tolerance_; }
    double floor() const { return floor_; }
    /// @}
    double answered() const { return answered_; }  ///< the fraction of the pieces that answer

private:
    static constexpr int shift = 52 - sub_bits;
    static constexpr std::uint64_t low_mask = (std::uint64_t{1} << shift) - 1;

    std::uint64_t first_ = 0;  ///< the piece index of 2^lowest_binade
    std::vector<std::array<double, 4>> coef_;
    std::vector<bool> in_log_;  ///< the piece's cubic is of ln f
    double tolerance_ = 0.0, floor_ = 0.0, answered_ = 0.0;
};

}  // namespace smithlab::detail
