// smithlab eval: Lambda and G1 for one (ndf, mu) or for every row of a CSV file.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "cli/commands.hpp"
#include "smithlab/csv.hpp"
#include "output/output_file.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

namespace {

// The route --method names: one of the core methods (method_names, with --backend and --tolerance), or a
// registered variant.
struct Route {
    LambdaOptions options;
    const LambdaVariant* variant = nullptr;
    // Lambda of ndf at a finite mu > 0, the variant prepared once per NDF (a table variant builds its table there).
    LambdaOfMu prepare(const AnyNdf& ndf) const {
        if (variant) return smithlab::prepare(*variant, ndf);
        return [ndf, o = options](double mu) { return smithlab::Lambda(ndf, mu, o); };
    }
};

// An NDF of the input and its Lambda by the route, made on the first row that names its spec.
struct Prepared {
    AnyNdf ndf;
    LambdaOfMu Lambda_up;
};

Route route(const EvalArgs& a, const VariantRegistry& variants) {
    Route r;
    r.options.backend = parse_backend(a.backend);
    r.options.tolerance = a.tolerance;
    r.options.downward = parse_downward(a.downward);
    if (const Named<Method>* m = find_named(method_names, a.method))
        r.options.method = m->value;
    else
        r.variant = &variants.at(a.method);
    return r;
}

// One Lambda evaluation serves both: G1 takes |mu| (Walter 2007 eq. 44), Lambda(mu < 0) follows the convention
// (the special values of mu: smith.hpp's Lambda_of_abs and Lambda_of_sign).
std::pair<double, double> lambda_g1(const Prepared& p, double mu, Downward downward) {
    try {
        const double up = Lambda_of_abs(mu, p.Lambda_up);
        return {Lambda_of_sign(mu, up, downward), 1.0 / (1.0 + up)};
    } catch (const input_error& e) {
        throw input_error("ndf '" + p.ndf.spec() + "': " + e.what());
    }
}

Prepared prepare(const std::string& spec, const NdfRegistry& registry, const Route& r) {
    AnyNdf ndf = registry.make(spec);
    if (!ndf.note().empty()) std::fprintf(stderr, "smithlab: note: %s\n", ndf.note().c_str());
    try {
        LambdaOfMu up = r.prepare(ndf);
        return {std::move(ndf), std::move(up)};
    } catch (const input_error& e) {
        throw input_error("ndf '" + ndf.spec() + "': " + e.what());
    }
}

int eval_csv(const EvalArgs& a, const NdfRegistry& registry, const Route& o) {
    // The output is checked before any work: a path that cannot be written, or is the input, is refused now.
    std::optional<output::OutputTarget> target;
    if (!a.output.empty() && a.output != "-") target = output::resolve_output(a.output, {a.input});
    std::ifstream file;
    if (a.input != "-") {
        output::require_readable_input(a.input, "input file");
        file.open(a.input, std::ios::binary);
        if (!file) throw input_error("cannot open input file '" + a.input + "'");
    }
    const std::vector<CsvRecord> records = read_csv(a.input == "-" ? std::cin : file);
    const std::string src = a.input == "-" ? "<stdin>" : a.input;
    if (records.empty()) throw input_error(src + ": empty file, expected a header with columns ndf and mu");
    const CsvRecord& head = records.front();
    if (!head.error.empty()) throw input_error(src + ":" + std::to_string(head.line) + ": header: " + head.error);
    int ndf_col = -1, mu_col = -1;
    for (std::size_t k = 0; k < head.fields.size(); ++k) {
        const std::string& h = head.fields[k];
        int* col = h == "ndf" ? &ndf_col : h == "mu" ? &mu_col : nullptr;
        if (col && *col >= 0) throw input_error(src + ":" + std::to_string(head.line) + ": header has two '" + h + "' columns");
        if (col) *col = static_cast<int>(k);
        if (h == "lambda" || h == "g1")
            throw input_error(src + ": header already has a '" + h + "' column, which eval would write");
    }
    if (ndf_col < 0 || mu_col < 0)
        throw input_error(src + ": header must have columns 'ndf' and 'mu' (got: " + [&] {
            std::string s;
            for (const auto& h : head.fields) s += (s.empty() ? "" : ",") + h;
            return s;
        }() + ")");

    std::ostringstream out;
    std::vector<std::string> header = head.fields;
    header.push_back("lambda");
    header.push_back("g1");
    write_csv_record(out, header);

    std::map<std::string, Prepared> cache;  // rows usually repeat a handful of specs
    int bad = 0;
    const std::size_t rows = records.size() - 1;
    for (std::size_t i = 1; i < records.size(); ++i) {
        const CsvRecord& rec = records[i];
        try {
            if (!rec.error.empty()) throw input_error(rec.error);
            if (rec.fields.size() != head.fields.size())
                throw input_error("expected " + std::to_string(head.fields.size()) + " fields, got " +
                                  std::to_string(rec.fields.size()));
            const std::string& spec = rec.fields[ndf_col];
            auto it = cache.find(spec);
            if (it == cache.end()) it = cache.emplace(spec, prepare(spec, registry, o)).first;
            const double mu = parse_number(rec.fields[mu_col], "mu");
            const auto [lambda, g1] = lambda_g1(it->second, mu, o.options.downward);
            std::vector<std::string> row = rec.fields;
            row.push_back(format_g17(lambda));
            row.push_back(format_g17(g1));
            write_csv_record(out, row);
        } catch (const std::exception& e) {  // bad input, or a numeric failure on this row's values
            std::cerr << src << ":" << rec.line << ": " << e.what() << "\n";
            ++bad;
        }
        if (rows >= 2000 && i % (rows / 10) == 0) std::cerr << "eval: " << i << "/" << rows << " rows\n";
    }
    if (bad) {
        std::cerr << "smithlab: error: " << bad << " bad row(s) in " << src << "; no output written\n";
        return exit_bad_input;
    }
    if (target)
        output::write_output(*target, out.str());
    else
        std::cout << out.str();
    return exit_ok;
}

}  // namespace

void add_eval(CLI::App& app, EvalArgs& a) {
    CLI::App* c = app.add_subcommand("eval", "Evaluate Smith Lambda and G1 for one NDF and direction, or for a CSV file");
    c->footer(
        "Examples:\n"
        "  smithlab eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --mu 0.5\n"
        "  smithlab eval --ndf 'ggx(alpha=0.2)' --mu 2 --method quadrature2d --backend gsl\n"
        "  smithlab eval --input points.csv --output out.csv\n"
        "CSV (RFC 4180): a header with at least columns ndf and mu (quote the spec: \"ggx(alpha=0.1)\");\n"
        "other columns pass through; lambda and g1 are appended with 17 significant digits. A bad row is\n"
        "reported with its line number; then nothing is written and the exit code is 2.\n"
        "Methods: auto (closed form if the NDF has one, else fixed), closed, spline (GTR: Dimov's\n"
        "natural cubic spline in gamma), quadrature (the reduced 1D integral), quadrature2d (nested P22->P2->Lambda),\n"
        "and every variant of `smithlab eval --list-methods` (fixed tolerances, interpolants, approximations).");
    auto* ndf = c->add_option("--ndf", a.ndf, "NDF spec, e.g. 'ggx(alpha=0.2)'");
    auto* mu = c->add_option("--mu", a.mu, "mu = cot(theta_v); 0 (grazing), inf (normal) and mu < 0 (below) allowed");
    auto* in = c->add_option("--input", a.input, "CSV file of points ('-' for stdin)");
    c->add_option("--output", a.output, "output CSV file (default: stdout); written only if every row succeeds")->needs(in);
    ndf->excludes(in)->needs(mu);
    mu->excludes(in)->needs(ndf);
    c->add_option("--method", a.method, join_names(method_names, " | ", " | ") + ", or a variant from --list-methods")
        ->capture_default_str();
    c->add_flag("--list-methods", a.list_methods, "list every method and variant with a one-line description");
    add_backend_option(*c, a.backend);
    c->add_option("--tolerance", a.tolerance, "relative tolerance of the quadrature methods")
        ->capture_default_str()
        ->check(CLI::Range(1e-15, 0.1));
    c->add_option("--downward", a.downward, "Lambda for mu < 0: " + join_described(downward_names, " | ", " | "))
        ->capture_default_str()
        ->check(CLI::IsMember(names_of(downward_names)));
}

int run_eval(const EvalArgs& a, const NdfRegistry& registry, const VariantRegistry& variants) {
    if (a.list_methods) {
        for (const Named<Method>& m : method_names)
            std::printf("%-28s %s\n", std::string(m.name).c_str(), std::string(m.description).c_str());
        for (const LambdaVariant& v : variants.list()) std::printf("%-28s %s\n", v.name.c_str(), v.description.c_str());
        return exit_ok;
    }
    const Route o = route(a, variants);
    if (!a.input.empty()) return eval_csv(a, registry, o);
    if (a.ndf.empty()) throw input_error("eval needs --ndf SPEC --mu M, or --input FILE (see smithlab eval --help)");
    const double mu = parse_number(a.mu, "mu");
    const Prepared p = prepare(a.ndf, registry, o);
    const AnyNdf& ndf = p.ndf;
    const auto [lambda, g1] = lambda_g1(p, mu, o.options.downward);
    std::cout << "ndf     " << ndf.spec() << "\n"
              << "mu      " << format_g17(mu) << "\n"
              << "method  " << a.method;
    const Method m = o.options.method;
    if (!o.variant && (m == Method::quadrature || m == Method::quadrature2d || m == Method::fixed ||
                       (m == Method::automatic && !ndf.has_closed_Lambda())))
        std::cout << " (" << a.backend << ", relative tolerance " << a.tolerance << ")";
    std::cout << "\nlambda  " << format_g17(lambda) << "\ng1      " << format_g17(g1) << "\n";
    return exit_ok;
}

}  // namespace smithlab::cli
