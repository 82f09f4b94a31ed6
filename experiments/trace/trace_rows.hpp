// trace/trace_rows.hpp -- trace's tables: albedo.csv and brdf.csv, a cell's rows and the files they are assembled in.
//
// albedo.csv: ndf,PARAMS,material,theta_i,phi_i,hemisphere,order,component,albedo,stderr,walks
// brdf.csv:   ndf,PARAMS,material,theta_i,phi_i,hemisphere,theta_o_lo,theta_o_hi,phi_o_lo,phi_o_hi,order,component,
//             value,stderr,walks
//   ndf         the NDF's spec; PARAMS: one column per parameter of the scene's NDFs (alpha, gamma, ...:
//               output/ndf_columns.hpp), empty where the row's NDF has no such parameter; a parameter named like one
//               of the table's own columns has no column of its own (the spec holds it)
//   material    the facets' material spec; theta_i, phi_i: the incident direction in degrees
//   hemisphere  reflection, transmission, or all (both)
//   theta_o_lo, theta_o_hi  a band of equal solid angle (equal steps of |cos theta_o|), in degrees from the macro
//               normal (transmission: from 90 to 180); phi_o_lo, phi_o_hi: an equal sector of phi_o in [0, 360)
//   order       the scattering order, as text: 1, 2 or 3 (the walk left after exactly that many facet hits), 4+ (four
//               hits or more), all (every order: the sum of the four)
//   component   specular (every event a facet reflection), diffuse (any diffuse event), or all (both)
//   albedo      the energy leaving into that selection per unit incident; value: f |cos theta_o| averaged over the
//               bin (1/sr); stderr: its standard error; walks: the cell's walks
// Numbers with 17 significant digits (they round-trip), the cell's direction as given.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "smithlab/any_ndf.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/trace.hpp"
#include "trace/cell_file.hpp"
#include "trace/trace_scene.hpp"

namespace smithlab::trace {

// The fields every row of a cell starts with (the NDF parameter columns aside) and ends with.
struct CellLabel {
    std::string ndf, material, theta_i, phi_i, walks;
};
CellLabel cell_label(const AnyNdf& ndf, const walk::Material& m, const TraceCell& cell, std::int64_t walks);

// A finished cell's rows of albedo.csv and (when its result has a directional tally) brdf.csv, its bounces and total.
CellRows cell_rows(const CellLabel& label, const walk::CellResult& r);

// The rows a cell has: albedo.csv's, and brdf.csv's for `bins` (both hemispheres for a material that transmits).
std::size_t albedo_row_count();
std::size_t brdf_row_count(const walk::BrdfBins& bins, bool transmits);

// albedo.csv, and brdf.csv when `brdf`, in dir: the header, then each cell's rows in cell order, the parameter
// columns of ndfs[i] (cell i's NDF) after the ndf column. Throws when a file cannot be written whole.
void write_tables(const std::filesystem::path& dir, std::span<const AnyNdf> ndfs, std::span<const CellRows> rows,
                  bool brdf);

}  // namespace smithlab::trace
