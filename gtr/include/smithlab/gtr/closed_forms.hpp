// smithlab/gtr/closed_forms.hpp -- Smith Lambda of GTR in closed form for gamma = 0, 1, 2, 3, 4 (Dimov 2015, sec. 3)
// and for every larger integer gamma (generated; Dimov stopped at 4 because gamma = 10 was "quite large"),
// rewritten so that every term is positive: each keeps full relative accuracy in double for all alpha in
// [1e-50, 1] and mu > 0. Dimov's printed forms, evaluated literally, lose up to all 16 digits (gamma = 3,
// alpha = 1e-4, mu >= 10: the difference mu - sqrt(mu^2 + alpha^2)).
#pragma once

namespace smithlab {

// Closed forms exist for every integer gamma in [0, gtr_max_closed_gamma].
inline constexpr int gtr_max_closed_gamma = 31;  // Ghat_k is integrated exactly for k <= 29
bool gtr_has_closed_form(double gamma);

// Lambda for integer gamma and finite mu > 0: the hand-derived forms below for gamma = 0..4, the generated sum
// (Lambda_gtr_integer_sum) above.
// With A = sqrt(mu^2 + alpha^2), B = sqrt(mu^2 + 1):
//   gamma = 0: 1 / (2 mu (mu + B))                                        (Dimov 3.1, (B - mu)/(2 mu) rationalized)
//   gamma = 1: h/((A+B)(mu+A)) [A/mu - log1pmx(x)/x],  x = (1-alpha^2)/((A+B)(mu+A)),  h = (1-alpha^2)/(-2 ln alpha)
//                                                                          (Dimov 3.2: log((mu+B)/(mu+A)) = log1p(x))
//   gamma = 2: alpha^2 / (2 mu (mu + A))                                   (Dimov 3.3, = GGX)
//   gamma = 3: w^2/(1+alpha^2) [(mu+A)/A + (1+3 alpha^2)/(4 mu A)],  w = alpha^2/(mu+A)          (Dimov 3.4)
//   gamma = 4: v^3/(16 c) [48 mu p^2 + 12 p^2/mu (1 + alpha^2 (5A+7mu)/(mu+A))
//                          + (3A + mu + 2 alpha^2 (3A+5mu) + alpha^4 (15A+37mu)) / (mu (mu+A)^3)],
//              v = alpha^2/A, p = mu/(mu+A), c = alpha^4 + alpha^2 + 1                         (Dimov 3.5)
double Lambda_gtr_closed(double alpha, int gamma, double mu);

// Any integer gamma >= 2, generated. With n = gamma - 2,
//   (r^2 + 1)^n = sum_k C(n, k) (1 - alpha^2)^k (r^2 + alpha^2)^(n - k),
// so P22 = K alpha^(2 gamma) sum_k C(n,k) (1-alpha^2)^k (r^2 + alpha^2)^-(2+k): a positive sum of Student-t-like slope
// laws, each with P2 = B(1/2, k+3/2) (q^2 + alpha^2)^-(k+3/2) (Walter 2007 eq. 43). Their Lambda integrals, with
// q = alpha tan(phi) and sin(phi_0) = mu/A, come to I_k = A^-(2k+1) b_k, where the bracket b_k has two exact forms
// (closed_forms.cpp, brackets()): one with a polynomial integrated exactly by Gauss-Legendre, used for mu < alpha,
// and one with every term positive, used for mu >= alpha, where the first would cancel by a factor 2k + 2. Then
//   Lambda = (K/mu) sum_k C(n,k) (1-alpha^2)^k B(1/2, k+3/2) alpha^(2(n-k)+3) (alpha/A)^(2k+1) b_k,
// every factor bounded and positive. gamma <= 31 keeps k <= 29 within the 30-node rule.
double Lambda_gtr_integer_sum(double alpha, int gamma, double mu);

}  // namespace smithlab
