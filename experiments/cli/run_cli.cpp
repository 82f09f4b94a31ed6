// smithlab::run_cli -- the command-line front end. `smithlab --help` and `smithlab COMMAND --help` explain
// everything; every command reads `smithlab COMMAND [SCENE] [OPTIONS]`, -o/--output naming what it writes.
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli/commands.hpp"
#include "cluster/mpi_world.hpp"
#include "output/signal_cleanup.hpp"
#include "output/standard_output.hpp"
#include "smithlab/cli.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/registry.hpp"

namespace smithlab::cli {

namespace {

// Every subcommand's arguments, filled by the parse.
struct Commands {
    EvalArgs eval;
    CheckArgs check;
    ReportArgs report;
    SampleArgs sample;
    TraceArgs trace;
    BrdfArgs brdf;
    FitArgs fit;
    TablesArgs tables;
    CLI::App* list = nullptr;
};

// The top-level help: the version, what smithlab does, and the NDFs this registry holds.
std::string description(const NdfRegistry& registry) {
    std::string names;
    for (const NdfInfo* info : registry.list()) names += (names.empty() ? "" : ", ") + info->name;
    return std::string("smithlab ") + SMITHLAB_VERSION +
        ": Smith masking-shadowing, normal sampling, path tracing and diffuse fitting for any isotropic\n"
        "microfacet NDF registered (here: " +
        names +
        ").\n"
        "NDFs are named by spec strings such as 'ggx(alpha=0.2)' or 'gtr(alpha=0.3, gamma=1.5)';\n"
        "`smithlab list` shows them all. mu = cot(theta) of the direction; mu < 0 points below the surface;\n"
        "angles are in degrees. Every command reads `smithlab COMMAND [SCENE] [OPTIONS]`; -o/--output names what\n"
        "it writes.";
}

void add_commands(CLI::App& app, Commands& c, const NdfRegistry& registry) {
    app.set_version_flag("--version", std::string("smithlab ") + SMITHLAB_VERSION, "print the version and exit");
    app.require_subcommand(1);
    add_eval(app, c.eval);
    add_check(app, c.check);
    add_report(app, c.report);
    add_sample(app, c.sample);
    add_trace(app, c.trace, registry.materials());
    add_brdf(app, c.brdf);
    add_fit(app, c.fit, registry.diffuse_models());
    add_tables(app, c.tables);
    c.list = add_list(app);
}

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

// Parses argv; an exit code where the run ends here (help, the version, a parse error: exit 2).
std::optional<int> parse(CLI::App& app, int argc, char** argv) {
    if (unknown_subcommand(app, argc, argv)) return exit_bad_input;
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --help-all, --version
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string where;
        for (const CLI::App* sub : app.get_subcommands()) where = " " + sub->get_name();
        std::cerr << "smithlab: error: " << e.what() << " (see smithlab" << where << " --help)\n";
        return exit_bad_input;
    }
    return std::nullopt;
}

int dispatch(CLI::App& app, const Commands& c, const NdfRegistry& registry, const VariantRegistry& variants) {
    if (cluster::mpi::size() > 1 && !app.got_subcommand("trace") && !app.got_subcommand("fit") &&
        !app.got_subcommand("report"))
        throw input_error(
            "only trace, fit and report run on several MPI ranks (they trace); run the others without mpirun");
    if (app.got_subcommand("eval")) return run_eval(c.eval, registry, variants);
    if (app.got_subcommand("check")) return run_check(c.check, registry);
    if (app.got_subcommand("report")) return run_report(c.report, registry, variants);
    if (app.got_subcommand("sample")) return run_sample(c.sample, registry);
    if (app.got_subcommand("trace")) return run_trace(c.trace, registry);
    if (app.got_subcommand("brdf")) return run_brdf(c.brdf, registry);
    if (app.got_subcommand("fit")) return run_fit(c.fit, registry);
    if (app.got_subcommand("tables")) return run_tables(c.tables, registry);
    if (c.list->parsed()) return run_list(registry);
    return exit_ok;
}

// The exit code of a failed run, said once. An error on one rank after the ranks started talking would leave the
// others waiting: it ends the whole job.
int fail(const char* what, const std::exception& e, int code) {
    if (cluster::mpi::size() > 1 && cluster::mpi::talking()) {
        std::cerr << "smithlab: " << what << " (rank " << cluster::mpi::rank() << " of " << cluster::mpi::size()
                  << "): " << e.what() << "\n";
        cluster::mpi::abort(code);
    }
    if (cluster::mpi::rank() == 0) std::cerr << "smithlab: " << what << ": " << e.what() << "\n";  // every rank's alike
    return code;
}

}  // namespace

}  // namespace smithlab::cli

// Declared in <smithlab/cli.hpp>; defined by its qualified name, so that this room opens only its own namespace.
int smithlab::run_cli(int argc, char** argv, const NdfRegistry& registry) {
    output::install_signal_cleanup();  // before any thread: outputs a signal interrupts leave no temporary
    // Under mpirun (and only there: a plain start never touches MPI), MPI_Init now and MPI_Finalize on the way out.
    cluster::mpi::init(argc, argv);
    struct Finalize {
        ~Finalize() { cluster::mpi::finalize(); }
    } finalize;
    output::StandardOutput standard_output;  // every write to it checked: a failed one is exit 2, named
    const VariantRegistry variants = builtin_variants();
    CLI::App app{cli::description(registry), "smithlab"};
    cli::Commands commands;
    cli::add_commands(app, commands, registry);
    try {
        const std::optional<int> done = cli::parse(app, argc, argv);
        const int code = done ? *done : cli::dispatch(app, commands, registry, variants);
        output::check_standard_output();  // what is still buffered, and what printf wrote
        return code;
    } catch (const input_error& e) {
        standard_output.quiet();
        return cli::fail("error", e, cli::exit_bad_input);
    } catch (const std::filesystem::filesystem_error& e) {  // a path the user gave that cannot be used
        standard_output.quiet();
        return cli::fail("error", e, cli::exit_bad_input);
    } catch (const std::exception& e) {
        standard_output.quiet();
        return cli::fail("internal error (please report it, with the command)", e, cli::exit_internal);
    }
}
