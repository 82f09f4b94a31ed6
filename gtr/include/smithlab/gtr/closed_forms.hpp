// smithlab/gtr/closed_forms.hpp -- Smith Lambda of GTR in closed form for gamma = 0, 1, 2, 3, 4 (Dimov 2015, sec. 3),
// rewritten so that every term is positive: each keeps full relative accuracy in double for all alpha in
// [1e-50, 1] and mu > 0. Dimov's printed forms, evaluated literally, lose up to all 16 digits (gamma = 3,
// alpha = 1e-4, mu >= 10: the difference mu - sqrt(mu^2 + alpha^2)).
#pragma once

namespace smithlab {

// True for gamma in {0, 1, 2, 3, 4}.
bool gtr_has_closed_form(double gamma);

// Lambda for integer gamma in 0..4 and finite mu > 0; throws input_error for any other gamma.
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

}  // namespace smithlab
