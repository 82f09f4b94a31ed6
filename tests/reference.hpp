// tests/reference.hpp -- independent high-precision references (Boost.Multiprecision, 50 digits).
//
// Independent of the code under test in three ways: 50-digit arithmetic; the slope densities written as printed in
// the papers (Dimov 2015's P22 for GTR, not smithlab's overflow-safe form); and the r-form of the reduced integral
//     Lambda(mu) = (2/mu) integral_mu^inf f(r^2) r (sqrt(r^2 - mu^2) - mu acos(mu/r)) dr
// integrated in r by tanh-sinh + exp-sinh, not the t-form smithlab integrates in double.
// The reference itself is validated against Dimov's printed closed forms (test_reference.cpp).
//
// Declarations only: the bodies are in tests/reference.cpp, compiled once (the object library smithlab_test_reference)
// and linked into the tests that include this header, instead of instantiating the 50-digit quadrature in each.
// The Boost headers stay included here: the includers use them (the multiprecision type, tanh-sinh and exp-sinh).
#pragma once

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace ref {

using real = boost::multiprecision::cpp_bin_float_50;
using boost::multiprecision::acos;
using boost::multiprecision::exp;
using boost::multiprecision::log;
using boost::multiprecision::pow;
using boost::multiprecision::sqrt;

real pi();

using SlopeDensity = std::function<real(const real& r2)>;

// Dimov 2015, P22 for GTR as printed: c (r^2 + 1)^(gamma-2) / (r^2 + alpha^2)^gamma,
// c = (gamma-1)(alpha^2-1) / (pi (1 - alpha^(2(1-gamma)))), gamma = 1: (alpha^2-1)/(pi ln alpha^2); alpha = 1: 1/pi.
real gtr_c(double alpha_d, double gamma_d);
// Burley 2012 / Dimov 2015 eq. (1**) as printed: D = c / (1 + (alpha^2 - 1) cos^2)^gamma.
real gtr_D(double alpha_d, double gamma_d, double cos_d);
SlopeDensity gtr(double alpha_d, double gamma_d);
SlopeDensity ggx(double alpha_d);
SlopeDensity beckmann(double alpha_d);
SlopeDensity blinn(double n_d);
// Ribardiere, Bringier, Meneveaux, Simonot 2017 (STD), the slope density as printed:
// (1 / (pi alpha^2)) (1 + r^2 / ((gamma - 1) alpha^2))^-gamma.
SlopeDensity student_t(double alpha_d, double gamma_d);

// The reduced integral in r, split at 2 mu: tanh-sinh on [mu, 2 mu], exp-sinh on [2 mu, inf).
real Lambda(const SlopeDensity& f, double mu_d);
// The same without the cut at r = 1e60 (1 + mu), for a tail heavier than r^-4 (the Student-t's r^(-2 gamma) leaves
// (1e60)^(3 - 2 gamma) of Lambda beyond it, 1e-12 at gamma = 1.6): exp-sinh integrates to infinity, in u = r / mu
// (scale-free, for mu up to 1e300).
real Lambda_uncut(const SlopeDensity& f, double mu_d);

// Ribardiere et al. 2017 eq. 13-14 as printed, at 100 digits, z = mu / alpha:
// Lambda = Gamma(gamma - 1/2) / (sqrt(pi) Gamma(gamma)) [(gamma - 1)^gamma S1 / (2 gamma - 3) + sqrt(gamma - 1) S2] -
// 1/2, S1 = ((gamma - 1) + z^2)^(3/2 - gamma) / z, S2 = integral_0^z (1 + u^2 / (gamma - 1))^(1/2 - gamma) du (eq. 15)
// by tanh-sinh. It cancels to 1/2 as z grows: 100 digits leave 50 wherever Lambda > 1e-45.
real Lambda_student_printed(double alpha_d, double gamma_d, double mu_d);

// Dimov 2015, the printed closed forms for gamma = 0..4 (sec. 3.1-3.5), evaluated literally at 100 digits: they
// cancel catastrophically (up to 32 digits for gamma = 4 at alpha = 1e-4, mu = 1e4), which leaves more than 60.
real Lambda_dimov(int gamma, double alpha_d, double mu_d);

// Beckmann closed form (Walter 2007 eq. 26 integrated): Lambda = (e^{-a^2}/(a sqrt(pi)) - erfc(a)) / 2, a = mu/alpha.
real Lambda_beckmann(double alpha_d, double mu_d);

double rel_err(double x, const real& ref);

// The acceptance rule of every accuracy test: relative error <= tol; where the true value underflows double,
// the answer must be 0 or a denormal, never NaN.
bool close(double got, const real& want, double tol);

}  // namespace ref
