#include "fit_trends.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include "smithlab/csv.hpp"
#include "staged_directory.hpp"

namespace smithlab::fitrun {

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
std::string formula(const Trend& t) {
    std::string out;
    for (Eigen::Index d = 0; d < t.p.size(); ++d) {
        char term[96];
        std::snprintf(term, sizeof term, "%s%.4g (+-%.2g)%s", d == 0 ? "" : t.p(d) < 0.0 ? " - " : " + ",
                      d == 0 ? t.p(d) : std::abs(t.p(d)), t.stderr_(d), d == 0 ? "" : d == 1 ? " gamma" : " gamma^2");
        out += term;
    }
    return out;
}

}  // namespace

std::string write_gamma_trends(const fs::path& dir, const Results& r) {
    std::vector<std::size_t> gtr;
    for (std::size_t n = 0; n < r.data.size(); ++n)
        if (r.data[n].family.family == "gtr" && r.data[n].family.gamma) gtr.push_back(n);
    if (gtr.size() < 3) return "";
    std::ofstream csv(dir / "gamma_trends.csv", std::ios::binary);
    write_csv_record(csv, {"model", "parameter", "form", "c0", "c1", "c2", "c0_stderr", "c1_stderr", "c2_stderr",
                           "chi2_dof", "max_deviation"});
    std::ostringstream md;
    md << "\n## The fitted constants against GTR's gamma\n\nEach constant of each fitted model as a line and as a "
          "parabola in gamma, by weighted least squares against the constants' standard errors (their spread over "
          "independent traces), with the coefficients' standard errors; chi^2 / dof near 1 where the form holds "
          "within that noise, and the form's largest deviation from the fitted constants, its error as a closed "
          "expression (gamma_trends.csv, and the plot pictures/constants_vs_gamma.png where drawn):\n\n"
          "| model | constant | line | chi^2/dof / max dev. | parabola | chi^2/dof / max dev. |\n"
          "|---|---|---|---:|---|---:|\n";
    for (std::size_t k = 0; k < r.fits[gtr[0]].size(); ++k) {
        const Measured& m0 = r.fits[gtr[0]][k];
        if (!m0.fitted()) continue;
        for (std::size_t i = 0; i < m0.params.size(); ++i) {
            std::vector<double> g, c, e;
            for (std::size_t n : gtr) {
                g.push_back(*r.data[n].family.gamma);
                c.push_back(r.fits[n][k].params[i]);
                e.push_back(r.fits[n][k].stderr_[i]);
            }
            const std::string param(m0.model->parameters[i]);
            md << "| " << m0.name << " | " << param << " |";
            for (int degree : {1, 2}) {
                const std::optional<Trend> t = polynomial_trend(g, c, e, degree);
                std::vector<std::string> row{m0.name, param, degree == 1 ? "line" : "parabola"};
                for (int part = 0; part < 2; ++part)
                    for (Eigen::Index d = 0; d < 3; ++d)
                        row.push_back(t && d <= degree ? format_g17(part == 0 ? t->p(d) : t->stderr_(d)) : "");
                row.push_back(t ? format_g17(t->chi2_dof) : "");
                row.push_back(t ? format_g17(t->deviation) : "");
                write_csv_record(csv, row);
                char fit[48];
                std::snprintf(fit, sizeof fit, "%.3g / %.2g", t ? t->chi2_dof : 0.0, t ? t->deviation : 0.0);
                md << " " << (t ? formula(*t) : std::string("(too few gammas, or an error of 0)")) << " | "
                   << (t ? fit : "") << " |";
            }
            md << "\n";
        }
    }
    output::finish(csv, dir / "gamma_trends.csv");
    return md.str();
}

}  // namespace smithlab::fitrun
