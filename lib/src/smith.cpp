#include "smithlab/smith.hpp"

#include <algorithm>
#include <array>
#include <boost/math/special_functions/beta.hpp>
#include <sstream>
#include <string>

namespace smithlab {

Method parse_method(std::string_view name) {
    if (const Named<Method>* m = find_named(method_names, name)) return m->value;
    throw input_error("unknown method '" + std::string(name) + "' (expected " + join_names(method_names, ", ", " or ") +
                      ")");
}

std::string_view to_string(Method m) { return name_of(method_names, m); }

Downward parse_downward(std::string_view name) {
    if (const Named<Downward>* d = find_named(downward_names, name)) return d->value;
    throw input_error("unknown downward convention '" + std::string(name) + "' (expected " +
                      join_names(downward_names, ", ", " or ") + ")");
}

namespace detail {

double tan_minus_x(double t, double tan_t) {
    if (t >= 0.5) return tan_t - t;  // cancellation at most a factor 11 here
    // Coefficients of t^3, t^5, ..., t^33 in tan(t) - t; at t = 0.5 the next term is below 1e-16 of the sum.
    static constexpr std::array<double, 16> c = {
        0.333333333333333333333,      0.133333333333333333333,      0.0539682539682539682540,
        0.0218694885361552028219,     0.00886323552990219656886,    0.00359212803657248101693,
        0.00145583438705131826825,    0.000590027440945585981378,   0.000239129114243552481486,
        0.0000969153795692945032560,  0.0000392783238833168340534,  0.0000159189050693289647407,
        0.00000645168921565543076319, 0.00000261477115129075455426, 0.00000105972683201046543509,
        4.29491107827380585482e-7};
    const double t2 = t * t;
    double p = c.back();
    for (auto it = c.rbegin() + 1; it != c.rend(); ++it) p = p * t2 + *it;
    return p * t2 * t;
}

// Below 1e-12 the grazing peak at s ~ mu/alpha and above 1e12 the underflow of f(r^2) r^2 leave the quadrature's
// tested range; closed forms have no such limit.
void require_mu(double mu) {
    require(mu >= 1e-12 && mu <= 1e12, "mu",
            "in [1e-12, 1e12] for the quadrature methods (0 and inf are handled exactly)", mu);
}

// r0 = 1 where P22(0) is 0 or not finite (no core scale to speak of: a plug-in's D(1) = 0); the factor 1 - 1e-9 lets
// r0 = 1.0000000000000004 (GTR(0.3, 0)) admit mu = 1e-12. The cap 1e-8 r0: the law's error bound P2(0) mu^2 / (2c)
// (grazing.hpp) is (mu/r0)^2 / 2 for GGX, 1e-16 there; above it, for r0 < 1e-4, the quadrature's refusal stands.
double quadrature_mu_min(double P22_at_pole) {
    const double r0 = core_slope_scale(P22_at_pole);
    return std::min(std::max(1e-12, 1e-12 * r0 * (1.0 - 1e-9)), 1e-8 * r0);
}

void require_quadrature_scale(double mu, double P22_at_pole, const char* method) {
    if (!(P22_at_pole > 0.0 && P22_at_pole < INFINITY)) return;  // no core scale to speak of (a plug-in's D(1) = 0)
    const double r0 = core_slope_scale(P22_at_pole);
    if (mu >= 1e-12 * r0 * (1.0 - 1e-9)) return;
    std::ostringstream msg;
    msg.precision(17);
    msg << "mu must be >= 1e-12 x the ndf's slope scale 1/sqrt(pi P22(0)) = " << r0 << " for the " << method
        << " methods (their grazing peak at mu/alpha is too narrow below; the closed form, where there is one, has no "
           "such limit), got "
        << mu;
    throw input_error(msg.str());
}

void require_slope_digits(double P22_at_pole, const char* method) {
    if (!(P22_at_pole > 0.0 && P22_at_pole < INFINITY)) return;
    const double r0 = core_slope_scale(P22_at_pole);
    if (r0 >= 1e-3) return;
    std::ostringstream msg;
    msg.precision(3);
    msg << "this ndf has only D(cos theta_m), and its slope scale 1/sqrt(pi P22(0)) = " << r0
        << " is below 1e-3: cos theta_m cannot carry the digits of such slopes (relative error ~1e-16 / scale^2 in "
           "Lambda), so the "
        << method << " methods refuse it; give the NDF a slope_density(r2) member (P22 as a function of tan^2 theta_m)";
    throw input_error(msg.str());
}

void require_finite_grazing_c(double T_R, double T_10R, double R) {
    if (!(T_R >= 0.0 && T_10R >= 0.0)) throw input_error("the grazing law: the slope density is negative or NaN");
    if (T_R == 0.0 || T_10R <= T_R * 0.8912509381337456) return;  // 10^-0.05: P22 falls faster than r^-3.05
    std::ostringstream msg;
    msg.precision(3);
    msg << "no grazing law (Lambda ~ c/mu as mu -> 0) for this ndf: its slope density falls no faster than r^-3.05 "
           "near tan(theta_m) = "
        << R << " (r^3 P22 = " << T_R << " there, " << T_10R
        << " at 10x), so c = E[q+] = 2 integral r^2 P22 dr is infinite or out of reach; Lambda has no finite value "
           "below the quadrature domain";
    throw input_error(msg.str());
}

void require_grazing_constants(double c, double P2_0) {
    if (c > 0.0 && c < INFINITY && P2_0 >= 0.0 && P2_0 < INFINITY) return;
    std::ostringstream msg;
    msg.precision(3);
    msg << "no grazing law for this ndf: c = E[q+] = " << c << " and P2(0) = " << P2_0
        << " (the quadrature of 2 integral r^2 P22 dr and 2 integral P22 dp) must be finite, c > 0";
    throw input_error(msg.str());
}

}  // namespace detail

double G2_from_Lambdas(double Lambda_i, double Lambda_o, bool same_side, G2Form form) {
    if (form == G2Form::uncorrelated) return 1.0 / ((1.0 + Lambda_i) * (1.0 + Lambda_o));
    if (same_side) return 1.0 / (1.0 + Lambda_i + Lambda_o);
    if (std::isinf(Lambda_i) || std::isinf(Lambda_o)) return 0.0;  // grazing: nothing is seen
    return boost::math::beta(1.0 + Lambda_i, 1.0 + Lambda_o);
}

}  // namespace smithlab
