// The report's G1 table: every Lambda variant the scene selects, on its grid (alpha x mu for each NDF), against an
// independent reference (references.hpp); the GTR family evaluator (gtr/family.hpp) also as a stream
// (gtr/family_stream.hpp), a row of its own. Writes variants.csv, the table of report.md, and for the figures the
// per-point errors (points/ROW.csv). The section that runs it: sections/g1.cpp.
#pragma once

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "report/references.hpp"
#include "report/timing.hpp"
#include "scene/scene_ndf.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::report {

struct PointError {
    std::size_t ndf;  // into G1Table::ndfs
    double mu, dG1, rel;
};

struct G1Row {
    const LambdaVariant* variant;
    bool stream = false;               // the family evaluator's stream (G1 at many points a call), not one call
    std::vector<std::size_t> ndfs;     // the NDFs it applies to (into G1Table::ndfs)
    std::vector<LambdaOfMu> prepared;  // one call: the variant prepared for each of them
    std::vector<PointError> errors;    // per point, kept only for the figures
    std::size_t points = 0;
    double max_dG1 = 0.0, sum_dG1 = 0.0, max_rel = 0.0;  // max_rel: not measured for the stream (its G1 only)
    std::size_t worst_ndf = 0;                           // where the worst error is: max_rel, or for the stream max_dG1
    double worst_mu = NAN;
    double ns = NAN;
    std::string name() const { return stream ? variant->name + "-stream" : variant->name; }
    std::string description() const;
};

struct G1Table {
    std::vector<AnyNdf> ndfs;    // each [[ndf]]'s points x alpha
    std::vector<double> alphas;  // the roughness each was made at (NaN: none, an entry that gives its own)
    std::vector<G1Row> rows;     // one per selected variant, and the stream after the family evaluator's
};

// The grid's NDFs and the selected variants: input_error for an unknown family or a scene that selects no variant.
G1Table g1_table(const std::vector<scene::NdfEntry>& entries, const std::vector<double>& alphas,
                 const NdfRegistry& ndfs, const VariantRegistry& variants, const std::vector<std::string>& include,
                 const std::vector<std::string>& exclude);
// input_error unless every grid mu is finite and > 0 and every quadrature a row runs (its own, its reference's)
// accepts it.
void require_g1_domain(const G1Table& table, const std::vector<double>& mus);

// Every row on every grid point it applies to, against the cached references; keeps the per-point errors if
// keep_errors (for the figures).
void measure_g1(G1Table& table, const std::vector<double>& mus, ReferenceCache& cache, bool keep_errors);
// One item per row: its Lambda (or its stream's G1) at the timing points of its grid (timing_points.hpp).
void add_g1_timing(G1Table& table, const std::vector<double>& mus, Timing& timing);

// Sorted by cost (ns/eval): DIR/variants.csv, and the grid's line and the table appended to DIR/report.md.
void write_g1_table(G1Table& table, const std::vector<double>& alphas, const std::vector<double>& mus,
                    const std::filesystem::path& dir);
// DIR/points/ROW.csv, one per row that kept its errors.
void write_g1_points(const G1Table& table, const std::filesystem::path& dir);

}  // namespace smithlab::report
