// The tables `smithlab eval` writes: one row per row of an input CSV (--input), or per point of a range
// (--mu-range, --theta-range). Each names its NDFs by spec with one column per NDF parameter beside it
// (output/ndf_columns.hpp), writes lambda and g1 with 17 significant digits, and writes nothing unless every row
// succeeds (exit 2, each bad row named).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/eval_points.hpp"
#include "evaluation/route.hpp"
#include "output/output_file.hpp"

namespace smithlab::cli {

int eval_csv(const EvalArgs& args, const NdfRegistry& registry, const evaluation::Route& route);
int eval_sweep(const EvalArgs& args, const std::vector<EvalPoint>& points, const NdfRegistry& registry,
               const evaluation::Route& route);

// The NDF `spec` names, from the registry, prepared for the route; its note (how it was built, where a user should
// know) on stderr.
evaluation::Prepared prepare(const std::string& spec, const NdfRegistry& registry, const evaluation::Route& route);

// The file -o names, checked before any work (a path that cannot be written, or is one of the inputs, is refused
// now); none for stdout ("" or "-").
std::optional<output::OutputTarget> csv_target(const std::string& output, const std::vector<std::string>& inputs);
// The table, to the file or to stdout.
void emit(const std::optional<output::OutputTarget>& target, const std::string& table);

}  // namespace smithlab::cli
