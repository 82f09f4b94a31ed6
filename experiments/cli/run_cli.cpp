// smithlab::run_cli -- the command-line front end. `smithlab --help` and `smithlab SUBCOMMAND --help` explain
// everything.
#include <exception>
#include <filesystem>
#include <iostream>

#include "cli/commands.hpp"
#include "cluster/mpi_world.hpp"
#include "output/signal_cleanup.hpp"
#include "smithlab/cli.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/registry.hpp"

namespace {

// CLI11 says only "A subcommand is required" for `smithlab frobnicate`: name it and list the known ones.
bool unknown_subcommand(CLI::App& app, int argc, char** argv) {
    if (argc < 2 || argv[1][0] == '-') return false;
    std::string known;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (sub->get_name() == argv[1]) return false;
        known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    std::cerr << "smithlab: error: unknown subcommand '" << argv[1] << "' (known: " << known
              << "; see smithlab --help)\n";
    return true;
}

}  // namespace

namespace smithlab {

int run_cli(int argc, char** argv, const NdfRegistry& registry) {
    output::install_signal_cleanup();  // before any thread: outputs a signal interrupts leave no temporary
    // Under mpirun (and only there: a plain start never touches MPI), MPI_Init now and MPI_Finalize on the way out.
    mpi::init(argc, argv);
    struct Finalize {
        ~Finalize() { mpi::finalize(); }
    } finalize;
    const VariantRegistry variants = builtin_variants();

    CLI::App app{
        "smithlab: Smith masking-shadowing, normal sampling, path tracing and diffuse fitting for any isotropic\n"
        "microfacet NDF registered (GGX, Beckmann, Blinn-Phong, GTR, Student-t, a tabulated D, a program's own).\n"
        "NDFs are named by spec strings such as 'ggx(alpha=0.2)' or 'gtr(alpha=0.3, gamma=1.5)';\n"
        "`smithlab list` shows them all. mu = cot(theta) of the direction; mu < 0 points below the surface.",
        "smithlab"};
    app.require_subcommand(1);

    cli::EvalArgs eval_args;
    cli::add_eval(app, eval_args);
    cli::CheckArgs check_args;
    cli::add_check(app, check_args);
    cli::ReportArgs report_args;
    cli::add_report(app, report_args);
    cli::SampleArgs sample_args;
    cli::add_sample(app, sample_args);
    cli::TraceArgs trace_args;
    cli::add_trace(app, trace_args);
    cli::BrdfArgs brdf_args;
    cli::add_brdf(app, brdf_args);
    cli::FitArgs fit_args;
    cli::add_fit(app, fit_args);
    CLI::App* list = app.add_subcommand("list", "List the registered NDFs, their parameters and example specs");

    if (unknown_subcommand(app, argc, argv)) return cli::exit_bad_input;
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return cli::exit_bad_input;
    }

    // An error on one rank after the ranks started talking would leave the others waiting: it ends the whole job.
    auto fail = [](const char* what, const std::exception& e, int code) {
        if (mpi::size() > 1 && mpi::talking()) {
            std::cerr << "smithlab: " << what << " (rank " << mpi::rank() << " of " << mpi::size() << "): " << e.what() << "\n";
            mpi::abort(code);
        }
        if (mpi::rank() == 0) std::cerr << "smithlab: " << what << ": " << e.what() << "\n";  // every rank's alike
        return code;
    };
    try {
        if (mpi::size() > 1 && !app.got_subcommand("trace") && !app.got_subcommand("fit") && !app.got_subcommand("report"))
            throw input_error("only trace, fit and report run on several MPI ranks (they trace); run the others without mpirun");
        if (app.got_subcommand("eval")) return cli::run_eval(eval_args, registry, variants);
        if (app.got_subcommand("check")) return cli::run_check(check_args, registry);
        if (app.got_subcommand("report")) return cli::run_report(report_args, registry, variants);
        if (app.got_subcommand("sample")) return cli::run_sample(sample_args, registry);
        if (app.got_subcommand("trace")) return cli::run_trace(trace_args, registry);
        if (app.got_subcommand("brdf")) return cli::run_brdf(brdf_args, registry);
        if (app.got_subcommand("fit")) return cli::run_fit(fit_args, registry);
        if (list->parsed()) {
            for (const NdfInfo* info : registry.list()) {
                std::cout << info->name << "(";
                for (std::size_t i = 0; i < info->parameters.size(); ++i) std::cout << (i ? ", " : "") << info->parameters[i];
                for (std::size_t i = 0; i < info->text_parameters.size(); ++i)
                    std::cout << (i || !info->parameters.empty() ? ", " : "") << info->text_parameters[i];
                std::cout << ")\n    " << info->description << "\n    e.g.";
                for (const auto& ex : info->examples) std::cout << "  " << ex;
                std::cout << "\n";
            }
            return cli::exit_ok;
        }
    } catch (const input_error& e) {
        return fail("error", e, cli::exit_bad_input);
    } catch (const std::filesystem::filesystem_error& e) {  // a path the user gave that cannot be used
        return fail("error", e, cli::exit_bad_input);
    } catch (const std::exception& e) {
        return fail("internal error (please report it, with the command)", e, cli::exit_internal);
    }
    return cli::exit_ok;
}

}  // namespace smithlab
