/// @file
/// smithlab/compensation/compensation_formats.hpp -- an energy-compensation table (compensation/albedo_grid.hpp's
/// AlbedoTable over (alpha, warped cosine x), with 1 - E_avg over alpha) written out for renderers: a C header, GLSL,
/// HLSL, and a 16-bit grey PNG with its axes in JSON; and the scattering orders' tables of conductor compensation
/// (compensation/scattering_orders.hpp) on such a grid: a C header, GLSL, HLSL and JSON.
///
/// Every lookup written computes AlbedoTable::lookup's rule in float: x = sqrt((1 + c) mu / (mu + c)), c the warp's
/// scale at the asked alpha (with a node cluster's share, albedo_grid.hpp, where the grid has one), cell j =
/// min(int(x (n_x - 1)), n_x - 2) and linear in x (in ln E, then exp, for a table of Stored::log); the alpha cell found
/// in sqrt(alpha) over the nodes' sqrt(alpha), linear in sqrt(alpha); below the first alpha the first row, above the
/// last the last row, both in the x of the asked alpha; mu clamped to [0, 1] (a renderer's dot products overshoot by a
/// rounding). The scale c and 1 - E_avg(alpha) follow lookup_power_law: ln of each linear in ln(alpha) between the
/// nodes, below the first alpha the first interval's power of alpha continued, above the last alpha the last value; the
/// files carry ln c and ln(1 - E_avg), not E_avg, so that Kulla and
/// Conty's lobe, divided by 1 - E_avg, keeps its relative precision where E_avg rounds to 1 as a float. Each file's top
/// comment says so, with the grid, the G2, the NDF family, the measured errors, and the formulas of Kulla and Conty
/// 2017 and Turquin 2019 that use the table (compensation/compensation.hpp).
///
/// Numbers are the floats nearest the table's doubles, written with 9 significant digits (a float's round trip).
#pragma once

#include <array>
#include <ostream>
#include <string>
#include <vector>

#include "smithlab/compensation/albedo_grid.hpp"

namespace smithlab::compensation {

/// What is written: a table over (alpha, x), the labels its comment gives, and the errors measured for it.
struct CompensationExport {
    std::string family;    ///< NDF family label, e.g. "ggx" or "gtr(gamma=1.5)"
    std::string g2;        ///< "height-correlated" or "separable"
    std::string quantity;  ///< e.g. "E" (mirror facets), or "E_R+E_T outside eta=1.5"; free text for the comment
    const AlbedoTable* E;  ///< the table over (alpha, x)
    /// 1 - E_avg at each alpha of E->grid.alphas (each finite, > 0 and <= 1, a normal float), or empty: no such array
    /// or lookup is written.
    std::vector<double> missing;
    double max_interp_error;  ///< measured at mu >= grazing_mu (albedo_grid.hpp), written in the comment
    double below_grid_error;  ///< measured error below the first alpha, written in the comment
    double grazing_error;     ///< measured at mu < grazing_mu, written in the comment
};

/// The names' prefix: "smithlab_" + the family as an identifier (compensation_header_name's rule: runs of other
/// characters than letters and digits become one '_'), "_hc" or "_sep" for the G2, and, when quantity is not "E", '_'
/// and the quantity made an identifier the same way: {"gtr(gamma=1.5)", "separable", "E_R+E_T outside eta=1.5"} ->
/// smithlab_gtr_gamma_1_5_sep_E_R_E_T_outside_eta_1_5. input_error for a family or quantity without a letter or digit,
/// or another G2.
std::string compensation_identifier(const CompensationExport& e);

// Each writer first checks the export (input_error naming the item): a table (E not null) on a valid grid
// (AlbedoGrid::check), n_alpha x n_x finite values that fit a float, the warp's scales normal floats, the alphas'
// square roots distinct as floats,
// missing empty or one value per alpha, each finite, > 0 and <= 1 and a normal float, the measured errors finite and
// >= 0.

/// The languages of the text formats, each a file of its own extension, one set of arrays and lookups in each:
///   c:    C99 (or C++), self-contained, in an include guard: static const float arrays, static inline functions;
///   glsl: GLSL 3.30 (no `#version` line: it goes after the includer's): const float arrays and functions;
///   hlsl: HLSL: static const float arrays and the same functions.
enum class Language { c, glsl, hlsl };
/// A text format: its language and its file's extension.
struct SourceFormat {
    Language language;      ///< the language written
    const char* extension;  ///< of its file: ".h", ".glsl", ".hlsl"
};
/// Every text format, in the order of Language.
inline constexpr std::array<SourceFormat, 3> source_formats{
    {{Language::c, ".h"}, {Language::glsl, ".glsl"}, {Language::hlsl, ".hlsl"}}};

/// The table in `language`: the arrays NAME_sqrt_alpha, NAME_log_scale (ln c at each alpha), NAME_E_table[n_alpha *
/// n_x] (row i = alphas[i]; NAME_log_E_table of ln E for a table of Stored::log) and NAME_log_missing_table (ln(1 -
/// E_avg) at each alpha), and the functions float NAME_E(float alpha, float mu), NAME_missing(alpha) = 1 - E_avg(alpha)
/// and NAME_E_avg(alpha) = 1 - NAME_missing(alpha), the same names in every language (the C header's guard:
/// NAME_COMPENSATION_H).
void write_source(std::ostream& out, const CompensationExport& e, Language language);
/// A grey 16-bit PNG (libpng), width n_x, height n_alpha, row i (from the top) = alphas[i], column j = x_j, pixel
/// round(E * 65535), or round(-ln(E) / K * 65535) for a table of ln E, K the largest -ln E (the JSON's log_scale), so
/// that a texture unit's bilinear filter interpolates ln E; input_error unless every E is in [0, 1], and then nothing
/// is written to out. The PNG's bytes, for the caller to write to a file as the other formats.
void write_png16(std::ostream& out, const CompensationExport& e);
/// The PNG's axes as JSON: family, g2, quantity, identifier, what is stored (E or ln E, with log_scale K), the alphas,
/// the warp's scales, n_x, the axis x (and its cluster), the lookup and outside rules, the 16-bit scale,
/// one_minus_E_avg and its lookup rule (when given), the measured errors.
void write_axes_json(std::ostream& out, const CompensationExport& e);

struct OrderTables;  // compensation/scattering_orders.hpp (its walk headers are not needed here)

/// What is written of the scattering orders (compensation/scattering_orders.hpp): the tables q_2, q_3, p and, for the
/// separable G2, q_1, with the labels and the worst standard error their comment gives.
struct OrderExport {
    std::string family;         ///< NDF family label, as CompensationExport's
    std::string g2;             ///< "height-correlated" or "separable"
    const OrderTables* orders;  ///< q_1 absent (no values) where the walk's G2 is the renderer's
    double max_stderr;          ///< the worst standard error of q_2 and q_3 over the nodes, written in the comment
};

/// compensation_identifier's prefix of the E table of the same family and G2, then "_orders": {"ggx",
/// "height-correlated"} -> smithlab_ggx_hc_orders. input_error as compensation_identifier's.
std::string order_identifier(const OrderExport& e);

/// Each writer of the orders first checks the export (input_error naming the item): tables (orders not null), a q_1
/// table for the separable G2 and none for the height-correlated one, q_2, q_3, p and q_1 stored as values on one grid
/// (alphas, scales, n_x and node cluster alike) that the E table's checks accept, n_alpha x n_x values each that fit a
/// float, q_2, q_3 and q_1 in [0, 1], p in (0, 1] as a normal float, max_stderr finite and >= 0.
///
/// The tables in `language` (as the E table's; the C header's guard: NAME_H): the arrays NAME_sqrt_alpha and
/// NAME_log_scale as the E table's, NAME_q2_table, NAME_q3_table, NAME_p_table and (separable G2)
/// NAME_q1_table[n_alpha * n_x]; the lookups NAME_q2(alpha, mu), NAME_q3, NAME_p and NAME_q1 by AlbedoTable::lookup's
/// rule in float, and NAME_ms(alpha, mu, E, F_avg) = multiple_scattering_albedo(E, orders at (alpha, mu), F_avg) in
/// float. The top comment states the formula, the NDF family, the G2, the grid and the worst standard error.
void write_source(std::ostream& out, const OrderExport& e, Language language);
/// The tables in JSON (row-major, as the arrays; no PNG: libpng's simplified API premultiplies 16-bit colour by the
/// alpha channel, which a fourth table would be) with their grid, lookup rules, formula and worst standard error.
void write_orders_axes_json(std::ostream& out, const OrderExport& e);

}  // namespace smithlab::compensation
