// smithlab fit: the diffuse fitter (lib/fit/, experiments/fit/) from the command line.
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "cluster/mpi_world.hpp"
#include "fit/fit_run.hpp"
#include "fit/fit_scene.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fit/diffuse_registry.hpp"

namespace smithlab::cli {

namespace {

// "Models (...): a, b, ...", wrapped before 115 columns as the rest of the footer.
std::string model_names(const fit::DiffuseRegistry& models) {
    std::string out = "Models (--list-models shows their sources and constants):";
    std::size_t column = out.size();
    for (const fit::DiffuseModel& m : models.list()) {
        const std::string word = std::string(m.name) + (&m == &models.list().back() ? "." : ",");
        const bool wrap = column + 1 + word.size() > 115;
        out += wrap ? "\n" : " ";
        column = (wrap ? 0 : column + 1) + word.size();
        out += word;
    }
    return out;
}

}  // namespace

void add_fit(CLI::App& app, FitArgs& a, const fit::DiffuseRegistry& models) {
    CLI::App* c = app.add_subcommand("fit", "Fit diffuse BRDF models to the path-traced Smith microsurface");
    c->footer(
        "Traces f(wi, wo) |cos theta_o| of a diffuse microsurface (Hammon 2017's fresnel-diffuse facets by default)\n"
        "by the eval estimator over alpha x (theta_i, theta_o, phi), split by the number of diffuse events so that "
        "one\n"
        "trace at albedo 1 serves every albedo; fits every diffuse model's free constants by weighted nonlinear least\n"
        "squares (GSL), and measures every model, fitted or at its published constants, on a validation set the fit\n"
        "never sees. With no scene it runs the embedded default (GGX; --print-scene shows it and documents every "
        "key).\n"
        "Examples:\n"
        "  smithlab fit\n"
        "  smithlab fit --print-scene > gtr.toml   # edit: [[ndf]] family = \"gtr\", gamma = [1, 1.5, 2, 3, 4]\n"
        "  smithlab fit gtr.toml -o gtr-fit/ --threads 8\n"
        "Writes into DIR (-o, default fit/): constants.csv (model,ndf,parameter,value,stderr) and constants.json;\n"
        "errors.csv (model,ndf,rms_rel,max_rel,albedo_rms,chi2_dof: on the validation set, chi2_dof per value with "
        "the\n"
        "fit's weights; '<model>' at its published constants, '<model>-fitted' refitted); training.csv and\n"
        "validation.csv (the traced values beside every model's); with [compensation] the energy-compensation\n"
        "tables of every NDF family and G2 (compensation.csv, compensation_avg.csv, compensation_dielectric.csv),\n"
        "their measured errors (compensation_error.csv), their furnace (furnace_tables.csv, furnace.csv against the\n"
        "walk, furnace.png) and compensation/ (C header, GLSL, HLSL, 16-bit PNG and JSON per table, docs/\n"
        "compensation.md); models.glsl and brdf/*.brdf (BRDF Explorer); for a family\n"
        "fitted at three or more values of one parameter FAMILY_PARAMETER_trends.csv (gtr_gamma_trends.csv); with\n"
        "[pictures] pictures/ (PNG and CSV); report.md; meta.json; all only\n"
        "when complete. Traced points are cached in DIR/cache/ as they finish: a killed run resumes, and refitting "
        "the\n"
        "same data (other models, albedos, floor) traces nothing.\n" +
        model_names(models));
    add_scene_options(*c, a.scene, a.print_scene, a.limits.scale, "the embedded default");
    add_output_option(*c, a.output, "output directory")->capture_default_str();
    add_threads_option(*c, a.threads);
    add_limit_options(*c, a.limits);
    c->add_flag("--list-models", a.list_models, "list the diffuse models, their constants and sources, and exit");
}

int run_fit(const FitArgs& a, const NdfRegistry& registry) {
    const fit::DiffuseRegistry& models = registry.diffuse_models();
    if (a.print_scene) {
        std::cout << fit::default_fit_scene_text();
        return exit_ok;
    }
    if (a.list_models) {
        for (const fit::DiffuseModel& m : models.list()) {
            std::cout << m.name << "\n    " << m.source << "\n    constants:";
            if (m.parameters.empty()) std::cout << " none (a fixed baseline)";
            for (std::size_t i = 0; i < m.parameters.size(); ++i)
                std::cout << " " << m.parameters[i] << " = " << m.published[i];
            std::cout << (m.glsl.get() ? "\n" : "\n    GLSL: has none\n");
        }
        return exit_ok;
    }
    require_threads(a.threads);
    require_scale(a.limits.scale);
    const std::string source = a.scene.empty() ? "<default scene>" : a.scene;
    const std::string text = a.scene.empty() ? fit::default_fit_scene_text() : read_scene_file(a.scene);
    const fit::FitScene scene = fit::parse_fit_scene(text, source, registry, a.limits);
    const fit::FitSummary sum = fit::run_fit(scene, source, text, registry, a.output, static_cast<unsigned>(a.threads));
    if (cluster::mpi::rank() != 0) return exit_ok;  // a rank of a run under mpirun: rank 0 reports
    std::printf("%-28s %-16s %10s %10s %10s %10s\n", "model", "ndf", "rms_rel", "max_rel", "albedo_rms", "chi2_dof");
    for (const fit::ErrorRow& r : sum.errors)
        std::printf("%-28s %-16s %10.4f %10.4f %10.5f %10.3g\n", r.model.c_str(), r.ndf.c_str(), r.rms_rel, r.max_rel,
                    r.albedo_rms, r.chi2_dof);
    std::printf("points %lld\ntraced %lld\nreused %lld\nseconds %.3g\noutput %s\n", static_cast<long long>(sum.points),
                static_cast<long long>(sum.traced), static_cast<long long>(sum.reused), sum.seconds, a.output.c_str());
    return exit_ok;
}

}  // namespace smithlab::cli
