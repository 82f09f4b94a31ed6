#include "evaluation/route.hpp"

#include <cmath>
#include <sstream>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::evaluation {

std::vector<std::pair<std::string, std::string>> method_list(const VariantRegistry& variants) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const Named<Method>& m : method_names) out.emplace_back(m.name, m.description);
    for (const LambdaVariant& v : variants.list()) out.emplace_back(v.name, v.description);
    return out;
}

LambdaOfMu Route::prepare(const AnyNdf& ndf, const std::shared_ptr<GrazingLawOnce>& law) const {
    if (variant) return smithlab::prepare(*variant, ndf);
    return [ndf, o = options, law](double mu) { return detail::Lambda_by_method(ndf, mu, o, law.get()); };
}

Route route(const RouteOptions& o, const VariantRegistry& variants) {
    Route r;
    r.options.backend = parse_backend(o.backend);
    r.options.tolerance = o.tolerance;
    r.options.downward = parse_downward(o.downward);
    if (const Named<Method>* m = find_named(method_names, o.method)) r.options.method = m->value;
    else r.variant = &variants.at(o.method);
    return r;
}

std::string describe(const Route& r, const RouteOptions& o, const AnyNdf& ndf, double mu) {
    std::ostringstream out;
    out << o.method;
    if (r.variant) return out.str();
    const double abs_mu = std::abs(mu);
    if (abs_mu > 0.0 && abs_mu < INFINITY && detail::answers_by_grazing_law(ndf, abs_mu, r.options)) {
        out << " (grazing law c/mu - 1/2 + P2(0) mu/2 below the quadrature domain, c = E[q+] by " << o.backend
            << " quadrature, relative tolerance " << o.tolerance << ")";
        return out.str();
    }
    const Method m = r.options.method;
    const bool closed = m == Method::automatic && ndf.has_closed_Lambda();
    // Lambda_by_method (smith.hpp): auto is the closed form where the NDF has one, else the fixed rule, which
    // answers by the adaptive route (the backend) where its error estimate misses the tolerance.
    if (closed) out << " (closed form)";
    if (m == Method::fixed || (m == Method::automatic && !closed))
        out << " (fixed rule, relative tolerance " << o.tolerance << "; " << o.backend
            << " where its error estimate misses it)";
    if (m == Method::quadrature || m == Method::quadrature2d)
        out << " (" << o.backend << ", relative tolerance " << o.tolerance << ")";
    return out.str();
}

Prepared prepare(AnyNdf ndf, const Route& r) {
    try {
        auto law = std::make_shared<GrazingLawOnce>();
        LambdaOfMu up = r.prepare(ndf, law);
        const bool exact = !r.variant && r.options.method != Method::spline;
        return {std::move(ndf), std::move(up), std::move(law), {r.options.backend, r.options.tolerance}, exact};
    } catch (const input_error& e) {
        throw input_error("ndf '" + ndf.spec() + "': " + e.what());
    }
}

LambdaG1 lambda_g1(const Prepared& p, double mu, Downward downward) {
    try {
        const double a = std::abs(mu);
        const double up = Lambda_of_abs(mu, p.Lambda_up);
        if (!(p.exact && up == INFINITY && a > 0.0)) return {Lambda_of_sign(mu, up, downward), 1.0 / (1.0 + up)};
        // An exact route overflowed (at mu of 1e-308 and below): both from the grazing law, exact there to rounding,
        // Lambda finite as long as c / mu is.
        const GrazingLaw& law = p.law->get(p.ndf, p.quadrature);
        return {Lambda_of_sign(mu, Lambda_grazing(law, a), downward), G1_grazing(law, a)};
    } catch (const input_error& e) {
        // Below the surface Lambda comes from |mu|: a message about |mu| says so, with mu as given.
        const std::string at =
            mu < 0.0 ? "at mu = " + format_shortest(mu) + ", from |mu| = " + format_shortest(-mu) + ": " : "";
        throw input_error("ndf '" + p.ndf.spec() + "': " + at + e.what());
    }
}

}  // namespace smithlab::evaluation
