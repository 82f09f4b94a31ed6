#include "smithlab/gtr/closed_forms.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "smithlab/errors.hpp"
#include "smithlab/gtr/gtr.hpp"

namespace smithlab {

namespace {

// Sum over the 30-node Gauss-Legendre rule on [0, 1] (Boost's tabulated nodes, exact to degree 59):
// visit(z, weight) for each node.
template <class Visit>
void for_each_gauss30_node(Visit visit) {
    using rule = boost::math::quadrature::gauss<double, 30>;
    const auto& x = rule::abscissa();  // the non-negative half of the nodes on [-1, 1]
    const auto& wt = rule::weights();
    for (std::size_t i = 0; i < x.size(); ++i) {
        visit(0.5 * (1.0 + x[i]), 0.5 * wt[i]);
        if (x[i] != 0.0) visit(0.5 * (1.0 - x[i]), 0.5 * wt[i]);
    }
}

// The brackets b_k = A^(2k+1) I_k, k = 0..n <= 29, of Lambda_gtr_integer_sum, by whichever of two exact forms
// has no cancellation where it is used:
//  mu <  alpha:  b_k = 1/(2k+1) - p (1-p)^k Ghat_k(w),  Ghat_k(w) = integral_0^1 z^k (2 - w z)^k dz, a polynomial
//                (exact by Gauss-Legendre); p <= 0.41 here and the cancellation stays below ~0.4 k.
//  mu >= alpha:  with s = alpha/A = sin(beta), sigma = sin(psi)/sin(beta) in the angular form of I_k,
//                b_k = 1/((2k+1)(2k+2)) + integral_0^1 sigma^(2k+1) x/(1 + sqrt(1 - x)) dsigma,
//                x = s^2 (1 - sigma^2)/(1 - s^2 sigma^2): every term positive; the integrand is analytic out to
//                sigma = 1/s >= sqrt(2), so Gauss-Legendre converges far below rounding.
// x^n for x in [0, 1], 0 <= n <= 29, by repeated squaring: at most 9 multiplications (within a few ulp of pow's
// correctly rounded value, at a tenth of its cost); an intermediate square underflows only where x^n does.
double power_of(double x, int n) {
    double r = 1.0;
    for (; n > 0; n >>= 1, x *= x)
        if (n & 1) r *= x;
    return r;
}

// 1 / (2k + 1), k = 0..29.
constexpr std::array<double, 30> inv_odd = [] {
    std::array<double, 30> r{};
    for (int k = 0; k < 30; ++k) r[k] = 1.0 / (2 * k + 1);
    return r;
}();

std::array<double, 30> brackets(int n, double alpha, double mu, double A) {
    std::array<double, 30> b{};
    if (mu < alpha) {
        const double p = mu / (A + mu), one_minus_p = A / (A + mu);
        const double w = alpha * alpha / (A * (A + mu));  // 1 - mu/A
        std::array<double, 30> G{};
        for_each_gauss30_node([&](double z, double weight) {
            const double u = z * (2.0 - w * z);
            double uk = weight;
            for (int k = 0; k <= n; ++k, uk *= u) G[k] += uk;
        });
        double pk = p;  // p (1 - p)^k, by running products (k <= 29: within 15 ulp of pow's)
        for (int k = 0; k <= n; ++k, pk *= one_minus_p) b[k] = inv_odd[k] - pk * G[k];
    } else {
        const double s2 = (alpha / A) * (alpha / A), m = mu / A;  // sin^2(beta), and cos(beta) = sqrt(1 - s2)
        for_each_gauss30_node([&](double sigma, double weight) {
            // x / (1 + sqrt(1 - x)) with 1 - x = m^2 / q, q = 1 - s2 sigma^2 >= 1/2 (s2 <= 1/2 here), is
            // s2 (1 - sigma^2) / (sqrt(q) (sqrt(q) + m)): one root and one division per node instead of two divisions.
            const double q = 1.0 - s2 * sigma * sigma, rq = std::sqrt(q);
            double term = weight * sigma * (s2 * (1.0 - sigma) * (1.0 + sigma)) / (rq * (rq + m));
            for (int k = 0; k <= n; ++k, term *= sigma * sigma) b[k] += term;
        });
        for (int k = 0; k <= n; ++k) b[k] += inv_odd[k] / (2.0 * k + 2);
    }
    return b;
}

}  // namespace

double Lambda_gtr_integer_sum(double alpha, int gamma, double mu) {
    if (gamma < 2 || gamma > gtr_max_closed_gamma)
        throw input_error("gtr: the generated closed form needs an integer gamma in [2, " +
                          std::to_string(gtr_max_closed_gamma) + "], got " + std::to_string(gamma));
    const int n = gamma - 2;
    const double a2 = alpha * alpha, one_minus_a2 = (1.0 - alpha) * (1.0 + alpha);
    const double A2 = mu * mu + a2, A = std::sqrt(A2);  // mu in [1e-100, 1e100]: no overflow (hypot not needed)
    const std::array<double, 30> b = brackets(n, alpha, mu, A);
    // The coefficients c_k = C(n, k) B(1/2, k + 3/2) b_k, and the polynomial in rho = (1 - alpha^2)/A^2 (header).
    std::array<double, 30> coef{};
    double cb = std::numbers::pi / 2;  // C(n, k) B(1/2, k + 3/2), starting from B(1/2, 3/2) = pi/2
    for (int k = 0; k <= n; ++k) {
        coef[k] = cb * b[k];
        cb *= (n - k) / (k + 1.0) * (k + 1.5) / (k + 2.0);  // C(n,k+1)/C(n,k) and B(1/2,k+5/2)/B(1/2,k+3/2)
    }
    double sum = 0.0, power = 0.0;
    if (one_minus_a2 <= A2) {  // rho <= 1: sum_k c_k rho^k, times alpha^(2n)
        const double rho = one_minus_a2 / A2;
        for (int k = n; k >= 0; --k) sum = sum * rho + coef[k];
        power = power_of(a2, n);
    } else {  // rho > 1: sum_k c_k rho^(k - n), times (alpha^2 rho)^n, alpha^2 rho <= 1
        const double inv_rho = A2 / one_minus_a2;
        for (int k = 0; k <= n; ++k) sum = sum * inv_rho + coef[k];
        power = power_of(a2 * (one_minus_a2 / A2), n);
    }
    // K alpha^2 <= (gamma - 1)/pi and alpha^2 / (mu A) are in range on the domain; the power underflows only where
    // Lambda does (rho <= 1 needs A^2 >= 1 - alpha^2; alpha^2 rho < 1e-11 needs mu > 1e5 alpha).
    return gtr_K(alpha, gamma) * a2 * (a2 / (mu * A)) * (power * sum);
}

double detail::Lambda_gtr_closed_far(double alpha, int gamma, double mu) {
    constexpr double big = gtr_closed::mu_big, small = gtr_closed::mu_small;
    if (mu > big) {
        const double r = big / mu;
        return Lambda_gtr_closed(alpha, gamma, big) * r * r;
    }
    if (mu < small) return Lambda_gtr_closed(alpha, gamma, small) * (small / mu);
    return mu;  // NaN
}

}  // namespace smithlab
