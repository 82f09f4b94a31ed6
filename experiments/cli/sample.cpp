// smithlab sample: microfacet normals drawn by a named sampler, as CSV rows x,y,z,pdf.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "cli/commands.hpp"
#include "evaluation/seed.hpp"
#include "output/output_file.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/samplers.hpp"

namespace smithlab::cli {

void add_sample(CLI::App& app, SampleArgs& a) {
    CLI::App* c = app.add_subcommand("sample", "Draw microfacet normals with a named sampler (CSV x,y,z,pdf)");
    c->footer(
        "Examples:\n"
        "  smithlab sample --ndf 'ggx(alpha=0.1)' --sampler vndf-ggx --theta-i 60 --n 100000 --seed 7 -o m.csv\n"
        "  smithlab sample --ndf 'gtr(alpha=0.2, gamma=1.5)' --sampler dcos --n 10\n"
        "  smithlab sample --list-samplers\n"
        "Each row is a unit normal m (z up) and its pdf with respect to solid angle. The incident direction is\n"
        "wi = (sin theta_i, 0, cos theta_i); the pdf of the mirror direction o = 2 (wi.m) m - wi is pdf / (4 wi.m).\n"
        "The same seed gives the same rows. The output file is written only when every sample is drawn.");
    c->add_option("--ndf", a.ndf, "NDF spec, e.g. 'ggx(alpha=0.2)'");
    c->add_option("--sampler", a.sampler, "sampler name (see --list-samplers)");
    c->add_option("--theta-i", a.theta_i, "incident polar angle in degrees, [0, 180) (above 90: below the surface)")
        ->capture_default_str()
        ->check(strict_real())
        ->check(CLI::Range(0.0, 179.999999));
    c->add_option("--n", a.n, "number of samples")
        ->capture_default_str()
        ->check(strict_integer())
        ->check(CLI::Range(1LL, 1000000000LL));
    add_seed_option(*c, a.seed);
    add_output_option(*c, a.output, "output CSV file (default: stdout)");
    c->add_flag("--list-samplers", a.list_samplers, "list the samplers with a one-line description");
}

int run_sample(const SampleArgs& a, const NdfRegistry& registry) {
    const std::vector<SamplerInfo> samplers = builtin_samplers();
    if (a.list_samplers) {
        for (const SamplerInfo& s : samplers) std::printf("%-12s %s\n", s.name.c_str(), s.description.c_str());
        return exit_ok;
    }
    if (a.ndf.empty() || a.sampler.empty())
        throw input_error("sample needs --ndf SPEC and --sampler NAME (see smithlab sample --help)");
    require(a.theta_i >= 0.0 && a.theta_i < 180.0, "--theta-i", "in [0, 180) degrees", a.theta_i);  // NaN too
    const unsigned long long seed = evaluation::parse_seed(a.seed, "--seed");
    std::optional<output::OutputTarget> target;  // checked before any work
    if (!a.output.empty() && a.output != "-") target = output::resolve_output(a.output);
    const AnyNdf ndf = registry.make(a.ndf);
    const BoundSampler sampler = prepare(find_sampler(samplers, a.sampler), ndf, direction_from_theta_deg(a.theta_i));
    // Rows stream out (a billion of them do not fit in memory); a file appears only when complete.
    auto write = [&](std::ostream& out) {
        Rng rng = make_rng(seed);
        write_csv_record(out, {"x", "y", "z", "pdf"});
        const auto n = static_cast<std::size_t>(a.n);
        for (std::size_t i = 0; i < n; ++i) {
            const NormalSample s = sampler.sample(rng);
            write_csv_record(out, {format_g17(s.m.x()), format_g17(s.m.y()), format_g17(s.m.z()), format_g17(s.pdf)});
            if (n >= 1000000 && (i + 1) % (n / 10) == 0) std::cerr << "sample: " << i + 1 << "/" << n << "\n";
        }
    };
    if (target) output::write_output(*target, write);
    else write(std::cout);
    return exit_ok;
}

}  // namespace smithlab::cli
