// smithlab eval: Lambda and G1 for one NDF at one direction (--mu or --theta), along a range of them
// (--mu-range, --theta-range), or for every row of a CSV file (--input).
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/eval_points.hpp"
#include "cli/eval_tables.hpp"
#include "evaluation/route.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

namespace {

// "  name  description" for each entry of the table, one a line (eval's help).
template <class E, std::size_t N>
std::string described_lines(const std::array<Named<E>, N>& table) {
    std::string out;
    for (const Named<E>& e : table) out += "  " + std::string(e.name) + ": " + std::string(e.description) + "\n";
    return out;
}

// The points' options, each excluding the others and --input; --output writes a table only.
void add_point_options(CLI::App& c, EvalArgs& a) {
    auto* in = c.add_option("--input", a.input, "CSV file of points, columns ndf and mu ('-' for stdin)");
    auto* mu = c.add_option("--mu", a.mu, "mu = cot(theta_v); 0 (grazing), inf (normal) and mu < 0 (below) allowed");
    auto* theta = c.add_option("--theta", a.theta, "theta_v in degrees from the normal, [0, 180] (above 90: below)");
    auto* mu_range = c.add_option("--mu-range", a.mu_range, "LO:HI:N or log:LO:HI:N, N >= 2 points of mu, as CSV");
    auto* theta_range = c.add_option("--theta-range", a.theta_range, "LO:HI:N, N >= 2 angles in degrees, as CSV");
    const std::vector<CLI::Option*> points = {in, mu, theta, mu_range, theta_range};
    for (CLI::Option* x : points)
        for (CLI::Option* y : points)
            if (x != y) x->excludes(y);
    c.add_option("--ndf", a.ndf, "NDF spec, e.g. 'ggx(alpha=0.2)'")->excludes(in);
    add_output_option(c, a.output,
                      "output CSV file of --input or a range (default: stdout); written only if every row succeeds");
}

int list_methods(const VariantRegistry& variants) {
    for (const auto& [name, description] : evaluation::method_list(variants))
        std::printf("%-28s %s\n", name.c_str(), description.c_str());
    return exit_ok;
}

// One point, as lines "key  value".
int eval_one(const EvalArgs& a, const EvalPoint& x, const NdfRegistry& registry, const evaluation::Route& route) {
    const evaluation::Prepared p = prepare(a.ndf, registry, route);
    const evaluation::LambdaG1 v = evaluation::lambda_g1(p, x.mu, route.options.downward);
    std::cout << "ndf     " << p.ndf.spec() << "\n";
    if (x.theta) std::cout << "theta   " << format_g17(*x.theta) << "\n";
    std::cout << "mu      " << format_g17(x.mu) << "\n"
              << "method  " << evaluation::describe(route, a.route, p.ndf, x.mu) << "\n"
              << "lambda  " << format_g17(v.lambda) << "\ng1      " << format_g17(v.g1) << "\n";
    return exit_ok;
}

}  // namespace

evaluation::Prepared prepare(const std::string& spec, const NdfRegistry& registry, const evaluation::Route& route) {
    AnyNdf ndf = registry.make(spec);
    if (!ndf.note().empty()) std::fprintf(stderr, "smithlab: note: %s\n", ndf.note().c_str());
    return evaluation::prepare(std::move(ndf), route);
}

std::optional<output::OutputTarget> csv_target(const std::string& output, const std::vector<std::string>& inputs) {
    if (output.empty() || output == "-") return std::nullopt;
    return output::resolve_output(output, inputs);
}

void emit(const std::optional<output::OutputTarget>& target, const std::string& table) {
    if (target) output::write_output(*target, table);
    else std::cout << table;
}

void add_eval(CLI::App& app, EvalArgs& a) {
    CLI::App* c = app.add_subcommand(
        "eval", "Evaluate Smith Lambda and G1 of an NDF at a direction, a range of them, or a CSV file");
    c->footer(
        "Examples:\n"
        "  smithlab eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --mu 0.5\n"
        "  smithlab eval --ndf 'ggx(alpha=0.2)' --theta 80 --method quadrature2d --backend gsl\n"
        "  smithlab eval --ndf 'ggx(alpha=0.2)' --mu-range log:0.01:100:41 -o ggx.csv\n"
        "  smithlab eval --ndf 'student(alpha=0.3, gamma=3)' --theta-range 0:90:19\n"
        "  smithlab eval --input points.csv -o out.csv\n"
        "A range writes CSV: ndf, one column per NDF parameter, theta (--theta-range), mu, lambda, g1.\n"
        "--input reads CSV (RFC 4180): a header with at least columns ndf and mu (quote the spec: "
        "\"ggx(alpha=0.1)\");\n"
        "other columns pass through, then one per NDF parameter not among them, then lambda and g1.\n"
        "Numbers are written with 17 significant digits. A bad row is reported with its line number; then nothing\n"
        "is written and the exit code is 2.\n"
        "Below the quadratures' domain (mu < 1e-12, or below 1e-12 x the NDF's slope scale r0 = 1/sqrt(pi P22(0)))\n"
        "and at mu <= 1e-8 r0, auto, quadrature, quadrature2d and fixed answer by the grazing law\n"
        "c/mu - 1/2 + P2(0) mu/2, c = E[q+] (docs/math.md); one point says so on its method line.\n"
        "Methods (--method):\n" +
        described_lines(method_names) +
        "  and every variant of `smithlab eval --list-methods` (fixed tolerances, interpolants, approximations).");
    add_point_options(*c, a);
    c->add_option("--method", a.route.method,
                  join_names(method_names, " | ", " | ") + ", or a variant from --list-methods")
        ->capture_default_str();
    c->add_flag("--list-methods", a.list_methods, "list every method and variant with a one-line description");
    add_backend_option(*c, a.route.backend);
    c->add_option("--tolerance", a.route.tolerance, "relative tolerance of the quadrature methods")
        ->capture_default_str()
        ->check(strict_real())
        ->check(CLI::Range(evaluation::min_tolerance, evaluation::max_tolerance));
    add_downward_option(*c, a.route.downward);
}

int run_eval(const EvalArgs& a, const NdfRegistry& registry, const VariantRegistry& variants) {
    if (a.list_methods) return list_methods(variants);
    const evaluation::Route route = evaluation::route(a.route, variants);
    if (!a.input.empty()) return eval_csv(a, registry, route);
    const bool range = !a.mu_range.empty() || !a.theta_range.empty();
    if (a.ndf.empty() || (a.mu.empty() && a.theta.empty() && !range))
        throw input_error(
            "eval needs --ndf SPEC with --mu, --theta, --mu-range or --theta-range, or --input FILE "
            "(see smithlab eval --help)");
    const std::vector<EvalPoint> points = eval_points(a.mu, a.theta, a.mu_range, a.theta_range);
    if (!range && !a.output.empty())
        throw input_error(
            "--output writes the CSV of --input or a range; one point is printed (see smithlab eval --help)");
    return range ? eval_sweep(a, points, registry, route) : eval_one(a, points.front(), registry, route);
}

}  // namespace smithlab::cli
