// smithlab check: the per-distribution checks, as a table.
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "output/standard_output.hpp"
#include "smithlab/checks.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

void add_check(CLI::App& app, CheckArgs& a) {
    CLI::App* c = app.add_subcommand("check", "Run the per-distribution checks and print each residual");
    c->footer(
        "Checks: integral of D cos = 1; G1(v) times the visible projected area = cos theta_v at theta_v = 30, 60,\n"
        "80, 89 deg; at mu = 0.1, 1, 10 (times the NDF's slope scale where above 1) the 1D quadrature of Lambda\n"
        "against the closed form (where one exists); without --no-2d, integral of P2 = 1 and the 1D against the\n"
        "nested 2D Lambda; an analytic D cos sampler leaves the probability it was asked for beyond its quantile\n"
        "(where one exists).\n"
        "Exit code 1 if any check fails, 2 for bad input.\n"
        "Examples:\n"
        "  smithlab check --ndf 'gtr(alpha=0.3, gamma=1.5)'\n"
        "  smithlab check --all");
    c->add_option("--ndf", a.ndfs, "NDF spec (repeatable)");
    c->add_flag("--all", a.all, "check every registered NDF at its example parameters (stiff corners included)");
    c->add_flag("--no-2d", a.no_2d, "skip the nested 2D checks (milliseconds per Lambda)");
    c->add_option(
         "--backend", a.backend,
         "quadrature backend: " + join_names(backend_names, " | ", " | ") +
             " (default: the one the NDF names, gsl for a tabulated D, whose kinks tanh-sinh does not resolve; "
             "else boost)")
        ->check(CLI::IsMember(names_of(backend_names)));
}

int run_check(const CheckArgs& a, const NdfRegistry& registry) {
    std::vector<std::string> specs = a.ndfs;
    if (a.all)
        for (const NdfInfo* info : registry.list())
            specs.insert(specs.end(), info->examples.begin(), info->examples.end());
    if (specs.empty()) throw input_error("check needs --ndf SPEC or --all (see smithlab check --help)");
    std::vector<AnyNdf> ndfs;
    for (const auto& s : specs) ndfs.push_back(registry.make(s));  // validate every spec before any work
    for (const AnyNdf& n : ndfs)
        if (!n.note().empty()) std::fprintf(stderr, "smithlab: note: %s\n", n.note().c_str());

    CheckOptions opts;
    opts.with_2d = !a.no_2d;
    int failed = 0, total = 0;
    std::printf("%-44s %-40s %-16s %-10s %-9s %s\n", "ndf", "check", "at", "residual", "tolerance", "");
    for (std::size_t i = 0; i < ndfs.size(); ++i) {
        if (ndfs.size() > 1) std::fprintf(stderr, "check: [%zu/%zu] %s\n", i + 1, ndfs.size(), ndfs[i].spec().c_str());
        opts.backend =
            a.backend.empty() ? ndfs[i].quadrature_backend().value_or(Backend::boost) : parse_backend(a.backend);
        for (const CheckResult& r : run_checks(ndfs[i], opts)) {
            ++total;
            failed += !r.passed();
            std::printf("%-44s %-40s %-16s %-10.2e %-9.0e %s\n", ndfs[i].spec().c_str(), r.name.c_str(),
                        r.where.c_str(), r.residual(), r.tolerance, r.passed() ? "ok" : "FAIL");
        }
        output::check_standard_output();  // a table that cannot be written stops here, not after every NDF
    }
    std::printf("%d passed, %d failed\n", total - failed, failed);
    return failed ? exit_failed : exit_ok;
}

}  // namespace smithlab::cli
