#include "fit/fit_trends.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

namespace {

// c(gamma) = sum_d p_d gamma^d, d <= degree, weighted by 1/e^2: p = (X^T X)^-1 X^T y with rows X_j = gamma_j^d / e_j,
// y_j = c_j / e_j; cov(p) = (X^T X)^-1.
struct Trend {
    Eigen::VectorXd p, stderr_;
    double chi2_dof = 0.0, deviation = 0.0;
};

std::optional<Trend> polynomial_trend(const std::vector<double>& g, const std::vector<double>& c,
                                      const std::vector<double>& e, int degree) {
    const Eigen::Index n = static_cast<Eigen::Index>(g.size()), k = degree + 1;
    if (n <= k) return std::nullopt;  // no degree of freedom left to judge the form by
    Eigen::MatrixXd X(n, k);
    Eigen::VectorXd y(n);
    for (Eigen::Index j = 0; j < n; ++j) {
        if (!(e[j] > 0.0)) return std::nullopt;
        for (Eigen::Index d = 0; d < k; ++d) X(j, d) = std::pow(g[j], static_cast<double>(d)) / e[j];
        y(j) = c[j] / e[j];
    }
    const Eigen::MatrixXd cov = (X.transpose() * X).inverse();
    Trend t{cov * X.transpose() * y, cov.diagonal().cwiseSqrt(), 0.0, 0.0};
    const Eigen::VectorXd r = X * t.p - y;
    t.chi2_dof = r.squaredNorm() / static_cast<double>(n - k);
    for (Eigen::Index j = 0; j < n; ++j) t.deviation = std::max(t.deviation, std::abs(r(j) * e[j]));
    return t;
}

// "0.122 (+-0.002) - 0.0082 (+-0.0007) gamma"
std::string formula(const Trend& t, const std::string& x) {
    std::string out;
    for (Eigen::Index d = 0; d < t.p.size(); ++d) {
        const char* sign = d == 0 ? "" : t.p(d) < 0.0 ? " - " : " + ";
        out += format_printf("%s%.4g (+-%.2g)", sign, d == 0 ? t.p(d) : std::abs(t.p(d)), t.stderr_(d));
        out += d == 0 ? "" : d == 1 ? " " + x : " " + x + "^2";
    }
    return out;
}

std::string write_trends(const fs::path& dir, const Results& r, const ParameterSweep& sweep) {
    const std::string name = sweep.family + "_" + sweep.parameter + "_trends.csv";
    std::ofstream csv(dir / name, std::ios::binary);
    write_csv_record(csv,
                     {"model", "parameter", "form", "c0", "c1", "c2", "c0_stderr", "c1_stderr", "c2_stderr", "chi2_dof",
                      "max_deviation"});
    const std::string x = sweep.parameter;
    std::ostringstream md;
    md << "\n## The fitted constants against " << sweep.family << "'s " << x << "\n\nEach constant of each fitted "
       << "model as a line and as a parabola in " << x << ", by weighted least squares against the constants' "
       << "standard errors (their spread over independent traces), with the coefficients' standard errors; chi^2 / dof "
       << "near 1 where the form holds within that noise, and the form's largest deviation from the fitted constants, "
       << "its error as a closed expression (" << name << ", and the plot pictures/constants_vs_" << sweep.family << "_"
       << x << ".png where drawn):\n\n"
       << "| model | constant | line | chi^2/dof / max dev. | parabola | chi^2/dof / max dev. |\n"
       << "|---|---|---|---:|---|---:|\n";
    for (std::size_t k = 0; k < r.fits[sweep.fits[0]].size(); ++k) {
        const Measured& m0 = r.fits[sweep.fits[0]][k];
        if (!std::all_of(sweep.fits.begin(), sweep.fits.end(), [&](std::size_t n) { return r.fits[n][k].fitted(); }))
            continue;
        for (std::size_t i = 0; i < m0.params.size(); ++i) {
            std::vector<double> c, e;
            for (std::size_t n : sweep.fits) {
                c.push_back(r.fits[n][k].params[i]);
                e.push_back(r.fits[n][k].stderr_[i]);
            }
            const std::string param(m0.model->parameters[i]);
            md << "| " << m0.name << " | " << param << " |";
            for (int degree : {1, 2}) {
                const std::optional<Trend> t = polynomial_trend(sweep.values, c, e, degree);
                std::vector<std::string> row{m0.name, param, degree == 1 ? "line" : "parabola"};
                for (int part = 0; part < 2; ++part)
                    for (Eigen::Index d = 0; d < 3; ++d)
                        row.push_back(t && d <= degree ? format_g17(part == 0 ? t->p(d) : t->stderr_(d)) : "");
                row.push_back(t ? format_g17(t->chi2_dof) : "");
                row.push_back(t ? format_g17(t->deviation) : "");
                write_csv_record(csv, row);
                md << " " << (t ? formula(*t, x) : "(too few values of " + x + ", or an error of 0)") << " | "
                   << (t ? format_printf("%.3g / %.2g", t->chi2_dof, t->deviation) : "") << " |";
            }
            md << "\n";
        }
    }
    output::finish(csv, dir / name);
    return md.str();
}

}  // namespace

std::vector<ParameterSweep> parameter_sweeps(const Results& r, std::size_t min_fits) {
    std::vector<ParameterSweep> out;
    std::vector<std::string> seen;
    for (const NdfData& first : r.data) {
        const std::string& family = first.family.family();
        if (std::find(seen.begin(), seen.end(), family) != seen.end()) continue;
        seen.push_back(family);
        std::vector<std::size_t> fits;
        for (std::size_t n = 0; n < r.data.size(); ++n)
            if (r.data[n].family.family() == family) fits.push_back(n);
        // The one parameter in which they differ: every other one equal across the fits.
        const scene::ParamPoint& p0 = r.data[fits[0]].family.params;
        std::vector<std::size_t> varying;
        for (std::size_t i = 0; i < p0.size(); ++i)
            for (std::size_t n : fits) {
                const scene::ParamPoint& p = r.data[n].family.params;
                if (p.size() != p0.size() || p[i].first != p0[i].first) {
                    varying.assign(p0.size() + 1, 0);  // not one family's sweep of one parameter
                    break;
                }
                if (p[i] != p0[i]) {
                    varying.push_back(i);
                    break;
                }
            }
        if (fits.size() < min_fits || varying.size() != 1) continue;
        ParameterSweep s{family, p0[varying[0]].first, fits, {}};
        for (std::size_t n : fits) s.values.push_back(r.data[n].family.params[varying[0]].second);
        out.push_back(std::move(s));
    }
    return out;
}

std::string write_parameter_trends(const fs::path& dir, const Results& r) {
    std::string md;
    for (const ParameterSweep& s : parameter_sweeps(r, 3)) md += write_trends(dir, r, s);
    return md;
}

}  // namespace smithlab::fit
