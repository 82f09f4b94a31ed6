// smithlab eval --mu-range / --theta-range: Lambda and G1 of one NDF at every point of a range, as CSV.
#include <sstream>

#include "cli/eval_tables.hpp"
#include "output/ndf_columns.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

int eval_sweep(const EvalArgs& a, const std::vector<EvalPoint>& points, const NdfRegistry& registry,
               const evaluation::Route& route) {
    const std::optional<output::OutputTarget> target = csv_target(a.output, {});
    const evaluation::Prepared p = prepare(a.ndf, registry, route);
    const bool by_angle = !a.theta_range.empty();
    const output::NdfColumns params = output::ndf_columns({&p.ndf, 1});
    std::vector<std::string> header = {"ndf"};
    header.insert(header.end(), params.names.begin(), params.names.end());
    if (by_angle) header.push_back("theta");
    header.insert(header.end(), {"mu", "lambda", "g1"});
    std::ostringstream out;
    write_csv_record(out, header);
    std::vector<std::string> row = {p.ndf.spec()};
    const std::vector<std::string> cells = params.cells(p.ndf);
    row.insert(row.end(), cells.begin(), cells.end());
    const std::size_t fixed = row.size();
    for (const EvalPoint& x : points) {  // an input_error on any point, naming it, leaves nothing written
        evaluation::LambdaG1 v;
        try {
            v = evaluation::lambda_g1(p, x.mu, route.options.downward);
        } catch (const input_error& e) {
            throw input_error(std::string(e.what()) + " (at mu = " + format_g17(x.mu) + ")");
        }
        row.resize(fixed);
        if (by_angle) row.push_back(format_shortest(*x.theta));
        row.insert(row.end(), {format_g17(x.mu), format_g17(v.lambda), format_g17(v.g1)});
        write_csv_record(out, row);
    }
    emit(target, out.str());
    return exit_ok;
}

}  // namespace smithlab::cli
