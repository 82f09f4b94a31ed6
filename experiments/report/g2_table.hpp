// The report's G2 table (the scene's [g2]): every selected G2 variant (Hammon's lerp, the uncorrelated forms)
// against the exact height-correlated G2 = 1/(1 + Lambda_i + Lambda_o), on alpha x mu_i x mu_o for the named
// families, with the cached references' Lambdas. Writes g2_variants.csv and a section of report.md. The section that
// runs it: sections/g2.cpp.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "report/references.hpp"
#include "report/timing.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::report {

struct G2Point {
    AnyNdf ndf;
    double mu_i, mu_o;
};

struct G2Row {
    G2Variant variant;
    std::vector<G2Point> grid;
    double max_d = 0.0, sum_d = 0.0, ns = NAN;
    std::size_t worst = 0;  // into grid
};

struct G2Table {
    std::vector<AnyNdf> ndfs;  // families x alpha; none without [g2]
    std::vector<G2Row> rows;   // one per selected variant
};

// The NDFs (families x alphas) and the variants include selects, checked: input_error for an unknown family, or a
// mu not finite and > 0 or at which the exact G2's quadrature (for an NDF without a closed-form Lambda) refuses to
// run. Empty for an empty include.
G2Table g2_table(const std::vector<std::string>& include, const std::vector<std::string>& families,
                 const std::vector<double>& alphas, const std::vector<double>& mus, const NdfRegistry& ndfs);

// Every row on every grid point it applies to, against the cached references.
void measure_g2(G2Table& table, const std::vector<double>& mus, ReferenceCache& cache);
// One item per row: its G2 at the timing points of its grid (timing_points.hpp).
void add_g2_timing(G2Table& table, Timing& timing);
// DIR/g2_variants.csv and its section appended to DIR/report.md; nothing if no row.
void write_g2_table(const G2Table& table, const std::filesystem::path& dir);

}  // namespace smithlab::report
