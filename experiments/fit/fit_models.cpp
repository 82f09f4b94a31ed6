#include "fit/fit_models.hpp"

#include <cstdio>
#include <iterator>

#include "smithlab/fit/fit_model.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::fit {

namespace {

// The model's errors on the validation set, its largest directional albedo and its grid checks.
ErrorRow measure(const NdfData& d, const Measured& m, const FitSettings& s) {
    const fit::FitData validation{d.validation, s.albedos, s.floor, {}};
    const fit::RelativeErrors rel = fit::relative_errors(*m.model, m.params, validation);
    const std::vector<double> thetas{0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 89.0};
    return {m.name,
            d.label,
            rel.rms,
            rel.max,
            fit::albedo_rms(*m.model, m.params, d.albedo, s.albedos),
            fit::chi2_per_value(*m.model, m.params, validation),
            fit::max_albedo(*m.model, m.params, s.training_alphas, thetas),
            fit::check_on_grid(*m.model, m.params, s.training_alphas)};
}

Measured fit(const NdfData& d, const fit::DiffuseModel& m, const FitSettings& s) {
    const fit::FitData training{d.training, s.albedos, s.floor,
                                s.energy_bound ? s.training_alphas : std::vector<double>{}};
    const fit::LeastSquaresFit f = fit::fit_model(m, training, d.label);
    return {std::string(m.name) + "-fitted", &m, f.params, f.stderr_, f.chi2_dof(), f.iterations};
}

}  // namespace

void FitProgress::starting(const std::string& ndf, std::size_t k, std::size_t n, const std::string& model) const {
    std::fprintf(stderr, "fit: %s: fitting and measuring model %zu of %zu (%s), %.0f s elapsed\n", ndf.c_str(), k + 1,
                 n, model.c_str(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

NdfFits fit_and_measure(const NdfData& d, const std::vector<const fit::DiffuseModel*>& models, const FitSettings& s,
                        const FitProgress& progress) {
    // One block a model, each a pure function of its model: the same rows, in the models' order, for any threads.
    auto one = [&](std::uint64_t k) {
        const fit::DiffuseModel& m = *models[k];
        progress.starting(d.label, k, models.size(), std::string(m.name));
        NdfFits out;
        const Measured start{std::string(m.name), &m, m.published, {}};
        const ErrorRow at_start = measure(d, start, s);
        if (m.own_baseline) {
            out.models.push_back(start);
            out.errors.push_back(at_start);
        }
        if (!m.parameters.empty()) {
            out.models.push_back(fit(d, m, s));
            out.errors.push_back(measure(d, out.models.back(), s));
            out.flags = flag_fit(out.models.back(), out.errors.back(), at_start);
        }
        return out;
    };
    auto append = [](NdfFits& all, NdfFits& f) {
        auto move_to_end = [](auto& to, auto& from) {
            to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
        };
        move_to_end(all.models, f.models);
        move_to_end(all.errors, f.errors);
        move_to_end(all.flags, f.flags);
    };
    return util::reduce_blocks(models.size(), s.threads, NdfFits{}, one, append, [](std::uint64_t) {});
}

}  // namespace smithlab::fit
