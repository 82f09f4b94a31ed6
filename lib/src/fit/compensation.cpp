#include "smithlab/fit/compensation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fresnel.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::fit {

namespace {

constexpr double pi = std::numbers::pi;
// Globally adaptive Gauss-Kronrod (GSL's QAG through smithlab's integrate: each call has its own workspace, so the
// nested integrals here are safe). Boost's adaptive Gauss-Kronrod halves the absolute tolerance with every level of
// its recursion instead, which round-off in a nested integrand never meets: 2^depth panels.
template <class F>
double gk(const F& f, double a, double b, double tolerance) {
    return integrate(f, a, b, {Backend::gsl, tolerance});
}

using detail::Event;

// The z of the direction refracted through a facet of normal m (m.z = mz), wi.m = c, wi.z = ci, eta the index below
// over the index above (Walter et al. 2007, eq. 40: wt = (c / eta - cos_t) m - wi / eta, cos_t = sqrt(1 - (1 - c^2) /
// eta^2)); 1 (not downward) under total internal reflection.
double refracted_z(double c, double mz, double ci, double eta) {
    const double k = 1.0 - (1.0 - c) * (1.0 + c) / (eta * eta);
    if (!(k > 0.0)) return 1.0;
    return (c / eta - std::sqrt(k)) * mz - ci / eta;
}

// Lambda of an outgoing direction of height z (either side of the surface), through |cot theta|.
double Lambda_of_z(FunctionRef Lambda, double z) {
    const double s = std::sqrt((1.0 - z) * (1.0 + z));
    return s > 0.0 ? Lambda(std::abs(z) / s) : 0.0;
}

// The grazing limit (mu -> 0) of the albedo of one event, wi = x: G2 / cos_i -> g(wo) / E[q+] with g = 1 for the
// height-correlated G2 of a reflection (1 / (1 + Lambda_i + Lambda_o) ~ 1 / Lambda_i, Lambda_i cos_i -> E[q+]), g =
// G1(wo) for the separable one, and, in transmission, g = G1(wo) separable and 0 height-correlated (B(1 + Lambda_i,
// 1 + Lambda_o) ~ Gamma(1 + Lambda_o) Lambda_i^-(1 + Lambda_o): light grazing the top of the surface does not reach
// below it). wi.m = r cos phi / sqrt(1 + r^2); every normal with cos phi > 0 reflects upward and refracts downward:
//     E(0) = integral_{p > 0} P22 p w(m) g(wo(m)) dp dq / integral_{p > 0} P22 p dp dq,
// w = F(wi.m) in reflection, 1 - F in transmission; in r = tan t (t in [0, pi/2]) and phi in [0, pi/2] (even in phi).
double grazing_albedo(FunctionRef P22, FunctionRef Lambda, const FunctionRef* F, const Event& event, double tolerance) {
    if (event.transmission && event.form == G2Form::height_correlated) return 0.0;
    auto radial = [&](double t, bool weighted) {
        if (t >= pi / 2) return 0.0;
        const double r = std::tan(t), c = std::cos(t), w = r * r * P22(r * r) / (c * c);  // r^2 P22 dr/dt
        if (!weighted || w == 0.0) return w;
        const double sin_m = std::sin(t);
        return w *
            gk(
                   [&](double phi) {
                       const double cm = sin_m * std::cos(phi);  // wi.m
                       const double f = event.transmission ? fresnel_dielectric(cm, event.eta) : F ? (*F)(cm) : 1.0;
                       const double wo_z = event.transmission ? refracted_z(cm, c, 0.0, event.eta) : 2.0 * cm * c;
                       if (event.transmission ? !(wo_z < 0.0) : !(wo_z > 0.0)) return 0.0;
                       const double g =
                           event.form == G2Form::uncorrelated ? 1.0 / (1.0 + Lambda_of_z(Lambda, wo_z)) : 1.0;
                       return std::cos(phi) * (event.transmission ? 1.0 - f : f) * g;
                   },
                   0.0, pi / 2, 0.1 * tolerance);
    };
    const double num = gk([&](double t) { return radial(t, true); }, 0.0, pi / 2, tolerance);
    const double den = gk([&](double t) { return radial(t, false); }, 0.0, pi / 2, tolerance);  // times integral of cos
    return num / den;
}

// E of one reflection at mu in (0, 1]: the quadrature of the header over [0, r1] x [0, pi] and {r1 < r < r_max,
// |phi| < phi_max(r)}.
double reflection_albedo(FunctionRef P22, FunctionRef Lambda, const FunctionRef* F, double mu, double tolerance,
                         G2Form form) {
    const double ci = mu, si = std::sqrt((1.0 - mu) * (1.0 + mu));
    const double Li = si > 0.0 ? Lambda(ci / si) : 0.0;
    // The integrand at (r, phi), without the measure r P22(r^2): (cos_i + sin_i r cos phi) G2 F, 0 below the horizon.
    auto facet = [&](double r, double cos_phi) {
        const double a = ci + si * r * cos_phi, n2 = 1.0 + r * r;               // a = (wi . m) sqrt(n2)
        const double woz = (ci * (1.0 - r * r) + 2.0 * si * r * cos_phi) / n2;  // wo = 2 (wi.m) m - wi
        if (!(woz > 0.0 && a > 0.0)) return 0.0;
        const double g = a * G2_from_Lambdas(Li, Lambda_of_z(Lambda, woz), true, form);
        return F ? g * (*F)(a / std::sqrt(n2)) : g;
    };
    const double inner_tol = 0.1 * tolerance;
    // [0, r1] x [0, pi]: every azimuth reflects above the horizon.
    const double r1 = ci / (1.0 + si), rmax = (1.0 + si) / ci;
    const double full = gk(
        [&](double r) {
            const double w = r * P22(r * r);
            if (w == 0.0) return 0.0;
            return w * gk([&](double phi) { return facet(r, std::cos(phi)); }, 0.0, pi, inner_tol);
        },
        0.0, r1, tolerance);
    // (r1, rmax): |phi| < phi_max(r), cos phi_max = -cos_i (1 - r^2) / (2 sin_i r); r = r1 (rmax / r1)^S(u),
    // S(u) = u^2 (3 - 2u): logarithmic in r (rmax / r1 = ((1 + sin_i) / cos_i)^2 grows without bound at grazing
    // incidence, and the slope law's features are O(1) wide in ln r), flat at both ends (dS/du = 0 there).
    double part = 0.0;
    if (si > 0.0 && rmax > r1) {
        const double L = 2.0 * std::log((1.0 + si) / ci);
        part = gk(
            [&](double u) {
                const double r = r1 * std::exp(L * u * u * (3.0 - 2.0 * u)), dr = r * L * 6.0 * u * (1.0 - u);
                const double w = r * P22(r * r) * dr;
                if (!(w > 0.0) || !(r > 0.0)) return 0.0;
                const double phi_max = std::acos(std::clamp(-ci * (1.0 - r * r) / (2.0 * si * r), -1.0, 1.0));
                if (!(phi_max > 0.0)) return 0.0;
                return w * phi_max * gk([&](double t) { return facet(r, std::cos(phi_max * t)); }, 0.0, 1.0, inner_tol);
            },
            0.0, 1.0, tolerance);
    }
    return 2.0 * (full + part) / ci;
}

// E_T of one refraction at mu in (0, 1] (Walter et al. 2007, eq. 21 integrated over wo: its Jacobian, eq. 17,
// cancels against dwo, leaving (1 / cos_i) integral D(m) (wi.m) (1 - F) G2(wi, wt(m)) dm), over every normal that
// sees wi (a > 0), in t = theta_m: t < pi/2 - theta_i at every azimuth, beyond it |phi| < phi_a(t),
// cos phi_a = -cot(theta_i) / tan t. The horizon of wt (wt.z = 0, where G2 -> 0) and the critical angle (where
// 1 - F -> 0 as a square root) are kinks inside the domain, left to the adaptive rule. G2 across the surface: B(1 +
// Lambda_i, 1 + Lambda_o) height-correlated (Heitz 2014, "Understanding the masking-shadowing function", eq. 101),
// G1 G1 separable.
double transmission_albedo(FunctionRef P22, FunctionRef Lambda, double mu, double tolerance, const Event& event) {
    const double ci = mu, si = std::sqrt((1.0 - mu) * (1.0 + mu));
    const double Li = si > 0.0 ? Lambda(ci / si) : 0.0;
    auto facet = [&](double t, double cos_phi) {  // the integrand without P22 r dr/dt
        const double r = std::tan(t), mz = std::cos(t);
        const double a = ci + si * r * cos_phi, c = a * mz;  // c = wi.m
        if (!(c > 0.0)) return 0.0;
        const double wz = refracted_z(c, mz, ci, event.eta);
        if (!(wz < 0.0)) return 0.0;
        const double f = fresnel_dielectric(c, event.eta);
        return a * (1.0 - f) * G2_from_Lambdas(Li, Lambda_of_z(Lambda, wz), false, event.form);
    };
    auto measure = [&](double t) {
        const double r = std::tan(t), c = std::cos(t);
        return r * P22(r * r) / (c * c);
    };
    const double inner_tol = 0.1 * tolerance;
    const double ta = si > 0.0 ? std::atan2(ci, si) : pi / 2;
    const double full = gk(
        [&](double t) {
            if (t >= pi / 2) return 0.0;
            const double w = measure(t);
            if (!(w > 0.0)) return 0.0;
            return w * gk([&](double phi) { return facet(t, std::cos(phi)); }, 0.0, pi, inner_tol);
        },
        0.0, ta, tolerance);
    double part = 0.0;
    if (ta < pi / 2) {
        part = gk(
            [&](double t) {
                if (t >= pi / 2) return 0.0;
                const double w = measure(t);
                if (!(w > 0.0)) return 0.0;
                const double phi_a = std::acos(std::clamp(-ci / (si * std::tan(t)), -1.0, 1.0));
                return w * phi_a * gk([&](double u) { return facet(t, std::cos(phi_a * u)); }, 0.0, 1.0, inner_tol);
            },
            ta, pi / 2, tolerance);
    }
    return 2.0 * (full + part) / ci;
}

}  // namespace

namespace detail {

double single_scattering_albedo(FunctionRef P22, FunctionRef Lambda, const FunctionRef* F, double mu, double tolerance,
                                const Event& event) {
    require(mu >= 0.0 && mu <= 1.0, "mu = cos(theta_i)", "in [0, 1]", mu);
    if (event.transmission) require(event.eta > 0.0 && std::isfinite(event.eta), "eta", "finite and > 0", event.eta);
    if (mu == 0.0) {
        if (!F && !event.transmission && event.form == G2Form::height_correlated) return 1.0;
        return grazing_albedo(P22, Lambda, F, event, tolerance);
    }
    return event.transmission ? transmission_albedo(P22, Lambda, mu, tolerance, event)
                              : reflection_albedo(P22, Lambda, F, mu, tolerance, event.form);
}

double cosine_average(FunctionRef e, double tolerance) {
    return 2.0 * integrate([&](double mu) { return e(mu) * mu; }, 0.0, 1.0, {Backend::boost, tolerance});
}

}  // namespace detail

std::vector<double> compensation_mus(int n) {
    require(n >= 2, "the number of table points", ">= 2", n);
    std::vector<double> mus(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) mus[static_cast<std::size_t>(j)] = static_cast<double>(j) / (n - 1);
    mus.back() = 1.0;
    return mus;
}

double interpolate_E(const CompensationTable& table, double mu) {
    const std::vector<double>& x = table.mus;
    if (x.size() < 2 || table.E.size() != x.size())
        throw input_error("compensation table: malformed (fewer than 2 points, or E and mus differ in size)");
    require(mu >= x.front() && mu <= x.back(), "mu", "within the table's cosines", mu);
    const std::size_t i = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), mu) - x.begin()), x.size() - 1);
    const std::size_t lo = i - 1;
    const double t = (mu - x[lo]) / (x[i] - x[lo]);
    return table.E[lo] + t * (table.E[i] - table.E[lo]);
}

double compensation_lobe(const CompensationTable& table, double mu_i, double mu_o) {
    const double missing = 1.0 - table.E_avg;
    if (!(missing > 0.0)) return 0.0;
    return (1.0 - interpolate_E(table, mu_i)) * (1.0 - interpolate_E(table, mu_o)) / (pi * missing);
}

double fresnel_ms(double F_avg, double E_avg) { return F_avg * F_avg * E_avg / (1.0 - F_avg * (1.0 - E_avg)); }

double kulla_conty_albedo(const AlbedoTable& E, const std::vector<double>& E_avg, double alpha, double mu_i,
                          double F_avg) {
    require(F_avg >= 0.0 && F_avg <= 1.0, "F_avg", "in [0, 1]", F_avg);
    const double avg = lookup_alpha(E.grid.alphas, E_avg, alpha);
    const double missing = 1.0 - avg;
    if (!(missing > 0.0)) return 0.0;
    // 8-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz and Stegun, table 25.4).
    static constexpr double x8[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static constexpr double w8[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    double integral = 0.0;
    for (int j = 0; j + 1 < E.grid.n_x; ++j) {
        const double a = unwarp_cosine(alpha, E.grid.x(j)), b = unwarp_cosine(alpha, E.grid.x(j + 1));
        const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
        for (int k = 0; k < 4; ++k)
            for (double sgn : {-1.0, 1.0}) {
                const double mu = mid + sgn * half * x8[k];
                integral += w8[k] * half * (1.0 - E.lookup(alpha, mu)) * mu;
            }
    }
    return fresnel_ms(F_avg, avg) * (1.0 - E.lookup(alpha, mu_i)) * 2.0 * integral / missing;
}

double turquin_scale(double E_view, double F0) {
    require(E_view > 0.0, "E(mu_view)", "> 0", E_view);
    return 1.0 + F0 * (1.0 - E_view) / E_view;
}

namespace {
std::string g17(double x) { return format_g17(x); }
std::string g9f(double x) {  // a float literal that round-trips the float nearest x
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9gf", static_cast<double>(static_cast<float>(x)));
    std::string s = buf;
    if (s.find_first_of(".eE") == std::string::npos) s.insert(s.size() - 1, ".0");
    return s;
}
}  // namespace

namespace {
// The first fields of table i's rows: its spec, then its cells of the extra columns.
std::vector<std::string> spec_fields(const std::string& spec, const SpecColumns& columns, std::size_t i) {
    std::vector<std::string> f{spec};
    if (columns.names.empty()) return f;
    f.insert(f.end(), columns.cells[i].begin(), columns.cells[i].end());
    return f;
}

void write_spec_header(std::ostream& out, const SpecColumns& columns, std::size_t tables,
                       const std::vector<std::string>& rest) {
    if (!columns.names.empty() && columns.cells.size() != tables)
        throw input_error("compensation CSV: " + std::to_string(columns.cells.size()) + " rows of columns for " +
                          std::to_string(tables) + " tables");
    for (const std::vector<std::string>& row : columns.cells)
        if (row.size() != columns.names.size())
            throw input_error("compensation CSV: a row of " + std::to_string(row.size()) + " cells for " +
                              std::to_string(columns.names.size()) + " columns");
    std::vector<std::string> header{"ndf"};
    header.insert(header.end(), columns.names.begin(), columns.names.end());
    header.insert(header.end(), rest.begin(), rest.end());
    write_csv_record(out, header);
}
}  // namespace

void write_compensation_csv(std::ostream& out, const std::vector<std::pair<std::string, CompensationTable>>& tables,
                            const SpecColumns& columns) {
    write_spec_header(out, columns, tables.size(), {"cos_theta", "E"});
    for (std::size_t i = 0; i < tables.size(); ++i) {
        const CompensationTable& t = tables[i].second;
        for (std::size_t j = 0; j < t.mus.size() && j < t.E.size(); ++j) {
            std::vector<std::string> row = spec_fields(tables[i].first, columns, i);
            row.push_back(format_shortest(t.mus[j]));
            row.push_back(g17(t.E[j]));
            write_csv_record(out, row);
        }
    }
}

void write_compensation_avg_csv(std::ostream& out, const std::vector<std::pair<std::string, CompensationTable>>& tables,
                                const SpecColumns& columns) {
    write_spec_header(out, columns, tables.size(), {"E_avg"});
    for (std::size_t i = 0; i < tables.size(); ++i) {
        std::vector<std::string> row = spec_fields(tables[i].first, columns, i);
        row.push_back(g17(tables[i].second.E_avg));
        write_csv_record(out, row);
    }
}

std::string compensation_header_name(std::string_view family_name) {
    std::string id = "smithlab_";
    bool sep = false;
    for (char c : family_name) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        if (ok) {
            if (sep && id.back() != '_') id += '_';
            id += c;
            sep = false;
        } else {
            sep = true;
        }
    }
    while (!id.empty() && id.back() == '_') id.pop_back();
    return id;
}

void write_compensation_header(std::ostream& out, std::string_view family_name, const std::vector<double>& alphas,
                               const std::vector<double>& mus, const std::vector<std::vector<double>>& E,
                               const std::vector<double>& E_avg) {
    if (alphas.size() < 2 || mus.size() < 2 || E.size() != alphas.size() || E_avg.size() != alphas.size())
        throw input_error(
            "compensation header: need >= 2 alphas and mus, E[alpha][mu] and E_avg[alpha] of the grid's sizes");
    for (const std::vector<double>& row : E)
        if (row.size() != mus.size()) throw input_error("compensation header: a row of E differs in size from mus");
    for (std::size_t i = 1; i < alphas.size(); ++i)
        if (!(alphas[i] > alphas[i - 1])) throw input_error("compensation header: alphas must ascend");
    for (std::size_t j = 1; j < mus.size(); ++j)
        if (!(mus[j] > mus[j - 1])) throw input_error("compensation header: mus must ascend");
    const std::string id = compensation_header_name(family_name);
    std::string guard = id;
    for (char& c : guard) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    guard += "_COMPENSATION_H";
    std::string family(family_name);
    for (std::size_t p; (p = family.find("*/")) != std::string::npos;) family.replace(p, 2, "* /");
    const std::size_t na = alphas.size(), nm = mus.size();

    out << "/* " << id << ": energy compensation for specular multiple scattering, NDF family " << family << ".\n"
        << " * Generated by smithlab (fit/compensation.hpp). E(alpha, mu): the directional albedo of single\n"
        << " * scattering off mirror facets (F = 1) with the height-correlated Smith G2 (Walter et al. 2007, eq. 20),\n"
        << " * mu = cos(theta); E_avg(alpha) = 2 int_0^1 E mu dmu. Kulla and Conty 2017: f_ms(wi, wo) =\n"
        << " * (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)), times F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) for\n"
        << " * coloured facets; Turquin 2019: f = f_ss (1 + F0 (1 - E(mu_view)) / E(mu_view)).\n"
        << " * " << id << "_E(alpha, mu) and " << id << "_E_avg(alpha) interpolate (bi)linearly, clamped to the grid:\n"
        << " * alpha in [" << g17(alphas.front()) << ", " << g17(alphas.back()) << "], mu in [" << g17(mus.front())
        << ", " << g17(mus.back()) << "]. Self-contained C99 (or C++). */\n"
        << "#ifndef " << guard << "\n#define " << guard << "\n\n";
    auto row = [&](const std::vector<double>& v) {
        std::string s;
        for (std::size_t k = 0; k < v.size(); ++k) {
            s += (k % 6 == 0 ? "\n    " : " ");
            s += g9f(v[k]);
            if (k + 1 < v.size()) s += ',';
        }
        return s;
    };
    out << "static const float " << id << "_alpha[" << na << "] = {" << row(alphas) << "\n};\n";
    out << "static const float " << id << "_mu[" << nm << "] = {" << row(mus) << "\n};\n";
    out << "static const float " << id << "_E_table[" << na << "][" << nm << "] = {";
    for (std::size_t i = 0; i < na; ++i) out << "\n  {" << row(E[i]) << "\n  }" << (i + 1 < na ? "," : "");
    out << "\n};\n";
    out << "static const float " << id << "_E_avg_table[" << na << "] = {" << row(E_avg) << "\n};\n\n";
    // The cell of x in an ascending grid g[0..n-1], clamped, and the weight of its upper end.
    out << "static inline int " << id << "_cell(const float* g, int n, float x, float* t) {\n"
        << "    int lo = 0, hi = n - 1;\n"
        << "    if (!(x > g[0])) { *t = 0.0f; return 0; }\n"
        << "    if (!(x < g[n - 1])) { *t = 1.0f; return n - 2; }\n"
        << "    while (hi - lo > 1) { int mid = (lo + hi) / 2; if (g[mid] <= x) lo = mid; else hi = mid; }\n"
        << "    *t = (x - g[lo]) / (g[lo + 1] - g[lo]);\n"
        << "    return lo;\n"
        << "}\n\n";
    out << "/* E(alpha, mu), bilinear in (alpha, mu). */\n"
        << "static inline float " << id << "_E(float alpha, float mu) {\n"
        << "    float ta, tm;\n"
        << "    int i = " << id << "_cell(" << id << "_alpha, " << na << ", alpha, &ta);\n"
        << "    int j = " << id << "_cell(" << id << "_mu, " << nm << ", mu, &tm);\n"
        << "    float lo = " << id << "_E_table[i][j] + tm * (" << id << "_E_table[i][j + 1] - " << id
        << "_E_table[i][j]);\n"
        << "    float hi = " << id << "_E_table[i + 1][j] + tm * (" << id << "_E_table[i + 1][j + 1] - " << id
        << "_E_table[i + 1][j]);\n"
        << "    return lo + ta * (hi - lo);\n"
        << "}\n\n";
    out << "/* E_avg(alpha), linear in alpha. */\n"
        << "static inline float " << id << "_E_avg(float alpha) {\n"
        << "    float ta;\n"
        << "    int i = " << id << "_cell(" << id << "_alpha, " << na << ", alpha, &ta);\n"
        << "    return " << id << "_E_avg_table[i] + ta * (" << id << "_E_avg_table[i + 1] - " << id
        << "_E_avg_table[i]);\n"
        << "}\n\n"
        << "#endif /* " << guard << " */\n";
}

}  // namespace smithlab::fit
