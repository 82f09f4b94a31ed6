#include "smithlab/fit/fit_model.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <numbers>

#include "smithlab/errors.hpp"

namespace smithlab::fit {

namespace {

// A point's traced values at the albedos, and the rows that whiten their residuals: C = V diag(lambda) V^T, row i
// lambda_i^-1/2 v_i^T for every lambda_i above 1e-12 of the largest. The values at several albedos are sums of the same
// few per-event means, so C can be singular (two events: rank 2); a direction without variance is one the data
// fixes exactly and carries no noise to weigh, and is left out (the pseudo-inverse), so that chi^2 counts only the
// directions there are.
struct Block {
    const DataPoint* point;
    Vec3 wi, wo;
    Eigen::VectorXd y;
    Eigen::MatrixXd whiten;  // rank x albedos
    Eigen::MatrixXd noise;   // the covariance of the whitened residuals from the data alone: whiten C whiten^T
};

std::vector<Block> blocks(const FitData& data) {
    std::vector<Block> out;
    const Eigen::Index na = static_cast<Eigen::Index>(data.albedos.size());
    for (const DataPoint& p : data.points) {
        Block b{&p, p.dir.wi(), p.dir.wo(), Eigen::VectorXd(na), {}, {}};
        Eigen::MatrixXd noise(na, na);
        for (Eigen::Index i = 0; i < na; ++i) {
            const AlbedoPower ai{data.albedos[i]};
            b.y(i) = at_albedo(p.moments, ai).value;
            for (Eigen::Index j = 0; j <= i; ++j)
                noise(i, j) = noise(j, i) = covariance(p.moments, ai, {data.albedos[j]});
        }
        Eigen::MatrixXd C = noise;
        for (Eigen::Index i = 0; i < na; ++i) C(i, i) += data.floor * data.floor * b.y(i) * b.y(i);
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(C);
        const double top = eig.eigenvalues().maxCoeff();
        if (!(top > 0.0)) continue;  // no variance at all (no walk reached wo): nothing to weigh it by
        std::vector<Eigen::Index> kept;
        for (Eigen::Index i = 0; i < na; ++i)
            if (eig.eigenvalues()(i) > 1e-12 * top) kept.push_back(i);
        b.whiten.resize(static_cast<Eigen::Index>(kept.size()), na);
        for (std::size_t r = 0; r < kept.size(); ++r)
            b.whiten.row(static_cast<Eigen::Index>(r)) =
                eig.eigenvectors().col(kept[r]).transpose() / std::sqrt(eig.eigenvalues()(kept[r]));
        b.noise = b.whiten * noise * b.whiten.transpose();
        out.push_back(std::move(b));
    }
    return out;
}

std::size_t residual_count(const std::vector<Block>& bs) {
    std::size_t n = 0;
    for (const Block& b : bs) n += static_cast<std::size_t>(b.whiten.rows());
    return n;
}

double value_at(const DiffuseModel& m, const double* c, const Block& b, double albedo) {
    return m.f(b.wi, b.wo, b.point->alpha, albedo, c) * b.wo.z();
}

// The residual that holds a directional albedo E to 1: (w / s) ln(1 + e^((E - 1) / w)), a smooth hinge (softplus of
// width w = 1e-4: a kinked max(0, E - 1) stalls Levenberg-Marquardt's finite-difference steps at the kink), steep
// beyond it (1 / s = 1e5 per unit of E); about 0 below 1 - 5w.
double energy_penalty(double E) {
    constexpr double w = 1e-4, s = 1e-5;
    const double x = (E - 1.0) / w;
    return w / s * (x > 30.0 ? x : std::log1p(std::exp(x)));
}

// r = whiten (model - y), block by block.
void residuals(const DiffuseModel& m, const std::vector<Block>& bs, const std::vector<double>& albedos, const double* c,
               std::span<double> r) {
    const std::size_t na = albedos.size();
    Eigen::VectorXd d(static_cast<Eigen::Index>(na));
    std::size_t at = 0;
    for (const Block& b : bs) {
        for (std::size_t a = 0; a < na; ++a) d(a) = value_at(m, c, b, albedos[a]) - b.y(a);
        const Eigen::VectorXd w = b.whiten * d;
        for (Eigen::Index i = 0; i < w.size(); ++i) r[at++] = w(i);
    }
}

// True when every diagonal entry of a covariance is finite and not negative.
bool usable(const Eigen::MatrixXd& cov) {
    for (Eigen::Index i = 0; i < cov.rows(); ++i)
        if (!(std::isfinite(cov(i, i)) && cov(i, i) >= 0.0)) return false;
    return true;
}

// (J^T J)^-1. Where the plain inverse is not usable, it is computed as D (J'^T J')^-1 D with J' = J D, D scaling
// each column of J to unit norm (Jacobi equilibration; the same matrix in exact arithmetic): a constant whose effect is
// tiny beside the others' (one that weighs the albedo^2 terms, fitted at an albedo of 1e-12) makes J^T J singular in
// double, not J'^T J'. A column of zeros (a constant with no effect on the data at all) is kept apart: its row and
// column of the result are 0 (data_statistics marks its standard error as not finite).
Eigen::MatrixXd inverse_normal(const Eigen::MatrixXd& J) {
    const Eigen::MatrixXd plain = (J.transpose() * J).inverse();
    if (usable(plain)) return plain;
    Eigen::VectorXd d(J.cols());
    for (Eigen::Index i = 0; i < J.cols(); ++i) d(i) = J.col(i).norm() > 0.0 ? 1.0 / J.col(i).norm() : 0.0;
    const Eigen::MatrixXd Js = J * d.asDiagonal();
    Eigen::MatrixXd A = Js.transpose() * Js;
    for (Eigen::Index i = 0; i < J.cols(); ++i)
        if (d(i) == 0.0) A(i, i) = 1.0;
    return d.asDiagonal() * A.inverse() * d.asDiagonal();
}

// chi^2, dof and the constants' covariance from the n data rows alone (the penalty rows after them are constraints,
// not data). The weights are not the data's inverse covariance where the floor adds to it, so the covariance is the
// sandwich (J^T J)^-1 J^T N J (J^T J)^-1, N the data's own covariance of the whitened residuals (Block::noise): the
// spread of the fitted constants over independent traces of the same scene. With floor 0, N = 1 and it is
// (J^T J)^-1. A standard error that is not finite (a constant the data does not determine) is left NaN for
// fit_model to refuse, never shown as 0.
void data_statistics(LeastSquaresFit& fit, const std::vector<Block>& bs, std::size_t n) {
    const Eigen::Index np = static_cast<Eigen::Index>(fit.params.size());
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
        fit.jacobian.data(), static_cast<Eigen::Index>(fit.residuals.size()), np);
    fit.chi2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) fit.chi2 += fit.residuals[i] * fit.residuals[i];
    fit.dof = static_cast<std::int64_t>(n) - np;
    const Eigen::MatrixXd Jd = J.topRows(static_cast<Eigen::Index>(n));
    const Eigen::MatrixXd bread = inverse_normal(Jd);
    Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(np, np);
    Eigen::Index row = 0;
    for (const Block& b : bs) {
        const Eigen::MatrixXd Jb = Jd.middleRows(row, b.whiten.rows());
        meat += Jb.transpose() * b.noise * Jb;
        row += b.whiten.rows();
    }
    const Eigen::MatrixXd cov = bread * meat * bread;
    for (Eigen::Index i = 0; i < np; ++i) {
        for (Eigen::Index j = 0; j < np; ++j) fit.covariance[static_cast<std::size_t>(i * np + j)] = cov(i, j);
        const bool no_effect = !(Jd.col(i).norm() > 0.0);
        fit.stderr_[static_cast<std::size_t>(i)] = cov(i, i) >= 0.0 && !no_effect ? std::sqrt(cov(i, i)) : std::nan("");
    }
}

// The first constant of m whose standard error is not finite, or none.
const std::string_view* undetermined(const DiffuseModel& m, const LeastSquaresFit& fit) {
    for (std::size_t i = 0; i < fit.stderr_.size(); ++i)
        if (!std::isfinite(fit.stderr_[i])) return &m.parameters[i];
    return nullptr;
}

}  // namespace

double model_value(const DiffuseModel& m, const std::vector<double>& params, const DataPoint& p, double albedo) {
    const Vec3 wo = p.dir.wo();
    return m.f(p.dir.wi(), wo, p.alpha, albedo, params.data()) * wo.z();
}

LeastSquaresFit fit_model(const DiffuseModel& m, const FitData& data, const std::string& what) {
    const std::vector<Block> bs = blocks(data);
    const std::size_t n = residual_count(bs);
    const std::size_t bounds = data.energy_alphas.size() * energy_thetas.size();
    LeastSquaresFit fit = least_squares(n + bounds, m.published, [&](std::span<const double> p, std::span<double> r) {
        residuals(m, bs, data.albedos, p.data(), r.first(n));
        const std::vector<double> c(p.begin(), p.end());
        std::size_t i = n;
        for (double a : data.energy_alphas)
            for (double t : energy_thetas) r[i++] = energy_penalty(model_albedo(m, c, a, t, 1.0));
    });
    if (fit.converged) data_statistics(fit, bs, n);
    if (const std::string_view* p = fit.converged ? undetermined(m, fit) : nullptr) {
        fit.converged = false;
        fit.reason = "the data does not determine its constant '" + std::string(*p) +
            "' (its standard error is not finite: at these albedos it changes no fitted value)";
    }
    if (!fit.converged)
        throw input_error("fit of model '" + std::string(m.name) + "' on " + what + " (" + std::to_string(bs.size()) +
                          " points x " + std::to_string(data.albedos.size()) + " albedos, " + std::to_string(n) +
                          " independent values): " + fit.reason);
    return fit;
}

double chi2_per_value(const DiffuseModel& m, const std::vector<double>& params, const FitData& data) {
    const std::vector<Block> bs = blocks(data);
    std::vector<double> r(residual_count(bs));
    if (r.empty()) return 0.0;
    residuals(m, bs, data.albedos, params.data(), r);
    double chi2 = 0.0;
    for (double v : r) chi2 += v * v;
    return chi2 / static_cast<double>(r.size());
}

RelativeErrors relative_errors(const DiffuseModel& m, const std::vector<double>& params, const FitData& data) {
    RelativeErrors e;
    double sum2 = 0.0;
    std::size_t n = 0;
    for (const DataPoint& p : data.points)
        for (double a : data.albedos) {
            const double y = at_albedo(p.moments, {a}).value;
            if (!(y > 0.0)) continue;
            const double rel = std::abs(model_value(m, params, p, a) - y) / y;
            sum2 += rel * rel;
            e.max = std::max(e.max, rel);
            ++n;
        }
    e.rms = n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
    return e;
}

double model_albedo(const DiffuseModel& m, const std::vector<double>& params, double alpha, double theta_i,
                    double albedo) {
    using boost::math::quadrature::gauss;
    const Vec3 wi = direction_from_deg(theta_i, 0.0);
    constexpr int n_phi = 64;
    const double* c = params.data();
    auto ring = [&](double mu) {  // the integral over phi of f cos theta_o at cos theta_o = mu, over pi / n_phi
        const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
        double sum = 0.0;
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) * std::numbers::pi / n_phi;
            sum += m.f(wi, Vec3(s * std::cos(phi), s * std::sin(phi), mu), alpha, albedo, c);
        }
        return sum * mu;
    };
    // Split at mu_o = mu_i, where the Oren-Nayar family's max / min of the two angles kinks.
    const double mi = std::clamp(wi.z(), 0.0, 1.0);
    const double integral = gauss<double, 20>::integrate(ring, 0.0, mi) + gauss<double, 20>::integrate(ring, mi, 1.0);
    return integral * 2.0 * std::numbers::pi / n_phi;  // dphi = pi / n_phi, and the half circle twice
}

double albedo_rms(const DiffuseModel& m, const std::vector<double>& params, const std::vector<DataPoint>& albedo_points,
                  const std::vector<double>& albedos) {
    double sum2 = 0.0;
    std::size_t n = 0;
    for (const DataPoint& p : albedo_points)
        for (double a : albedos) {
            const double d = model_albedo(m, params, p.alpha, p.dir.theta_i, a) - at_albedo(p.moments, {a}).value;
            sum2 += d * d;
            ++n;
        }
    return n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
}

AlbedoPeak max_albedo(const DiffuseModel& m, const std::vector<double>& params, const std::vector<double>& alphas,
                      const std::vector<double>& thetas) {
    AlbedoPeak peak;
    for (double a : alphas)
        for (double t : thetas)
            if (const double e = model_albedo(m, params, a, t, 1.0); e > peak.albedo) peak = {e, a, t};
    return peak;
}

GridCheck check_on_grid(const DiffuseModel& m, const std::vector<double>& params, const std::vector<double>& alphas) {
    GridCheck out;
    const double thetas[] = {0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0};
    for (double a : alphas)
        for (double ti : thetas)
            for (double to : thetas)
                for (double phi : {0.0, 45.0, 90.0, 135.0, 180.0})
                    for (double albedo : {0.5, 1.0}) {
                        const Vec3 wi = direction_from_deg(ti, 0.0), wo = direction_from_deg(to, phi);
                        const double x = m.f(wi, wo, a, albedo, params.data()),
                                     y = m.f(wo, wi, a, albedo, params.data());
                        out.min_f = std::min({out.min_f, x, y});
                        if (const double big = std::max(x, y); big > 0.0)
                            out.asymmetry = std::max(out.asymmetry, std::abs(x - y) / big);
                    }
    return out;
}

}  // namespace smithlab::fit
