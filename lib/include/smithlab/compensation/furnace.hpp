/// @file
/// smithlab/compensation/furnace.hpp -- the white furnace of a compensated BSDF by its tables: how far from 1 the
/// albedo comes that a renderer computes from them, at every point of a table's check grid.
///
/// Mirror facets (Kulla and Conty 2017, compensation.hpp): a renderer evaluates single scattering exactly and adds
/// their lobe from the tables of E and E_avg, so its albedo at albedo 1 is
///     E(alpha, mu) + kulla_conty_albedo(table, 1 - E_avg, alpha, mu),
/// E exact (the check grid's values), the lobe's albedo from the lookups. It is 1 where the table is exact; the
/// difference is the table's interpolation error in E and in the lobe's integral.
/// A dielectric (Turquin 2019, "Practical multiple scattering compensation for microfacet models", the dielectric
/// case): the single-scattering BSDF, reflection and transmission, divided by the table of E_R + E_T at the incident
/// cosine, so that its albedo is
///     (E_R + E_T)(alpha, mu) / table(alpha, mu),
/// and the reflected and transmitted parts keep the single scattering's ratio.
///
/// Both measure the compensation the tables give against its aim, 1, on the check grid (the values a renderer's lookup
/// never sees), down to a cosine mu_min: the walk (walk/trace.hpp) measures the aim itself against the multiply
/// scattered light of the Smith microsurface.
#pragma once

#include <vector>

#include "smithlab/compensation/albedo_grid.hpp"

namespace smithlab::compensation {

/// The worst |albedo - 1| over mu >= mu_min at each alpha of the check grid (t.fine.grid.alphas), and where.
/// missing: 1 - E_avg at E's alphas. Kulla and Conty's furnace of mirror facets from the table of E, and Turquin's of
/// a dielectric from the table of E_R + E_T (`sum`).
///@{
std::vector<InterpolationError> kulla_conty_furnace(const CheckedTable& E, const std::vector<double>& missing,
                                                    double mu_min);
std::vector<InterpolationError> turquin_furnace(const CheckedTable& sum, double mu_min);
///@}

/// The worst of a furnace's alphas.
InterpolationError worst_of(const std::vector<InterpolationError>& per_alpha);

}  // namespace smithlab::compensation
