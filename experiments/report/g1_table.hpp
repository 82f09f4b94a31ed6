// The report's G1 table: every Lambda variant the scene selects, on its grid (alpha x mu for each NDF), against an
// independent reference (references.hpp). Writes variants.csv, the table of report.md, and for the figures the
// per-point errors (points/VARIANT.csv).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "report/references.hpp"
#include "report/scene.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/variants.hpp"
#include "report/timing.hpp"

namespace smithlab::report {

// A grid point as the timing sees it: the variant prepared for the point's NDF (once per NDF, shared), and mu.
struct G1Point {
    std::shared_ptr<const LambdaOfMu> Lambda;
    double mu;
};

struct PointError {
    double alpha, gamma, mu, dG1, rel;
};

struct G1Row {
    const LambdaVariant* variant;
    std::vector<G1Point> grid;         // the grid points it applies to
    std::vector<PointError> errors;    // per point, kept only for the figures
    std::size_t points = 0;
    double max_dG1 = 0.0, sum_dG1 = 0.0, max_rel = 0.0;
    std::string worst_at;
    double ns = NAN;
};

struct G1Table {
    std::vector<AnyNdf> ndfs;     // each [[ndf]]'s points x alpha
    std::vector<double> alphas;   // the roughness each was made at (NaN: none, an entry that gives its own)
    std::vector<G1Row> rows;   // one per selected variant
};

// The grid's NDFs and the selected variants: input_error for an unknown family or a scene that selects no variant.
// The mu axis is checked apart (require_g1_domain), after every section's keys.
G1Table g1_table(const Scene& scene, const NdfRegistry& ndfs, const VariantRegistry& variants);
// input_error unless every quadrature a row runs (its own, its reference's) accepts every grid mu.
void require_g1_domain(const G1Table& table, const std::vector<double>& mus);

// Every row on every grid point it applies to, against the cached references; keeps the per-point errors if
// keep_errors (for the figures).
void measure_g1(G1Table& table, const std::vector<double>& mus, ReferenceCache& cache, bool keep_errors);
// One item per row: its Lambda at (at most 64 of) its grid points.
void add_g1_timing(G1Table& table, std::vector<Timed>& timed);

// Sorted by cost (ns/eval): DIR/variants.csv, and the grid's line and the table appended to DIR/report.md.
void write_g1_table(G1Table& table, const Scene& scene, const std::filesystem::path& dir);
// DIR/points/VARIANT.csv, one per row that kept its errors.
void write_g1_points(const G1Table& table, const std::filesystem::path& dir);

}  // namespace smithlab::report
