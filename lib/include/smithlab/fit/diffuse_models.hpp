/// @file
/// smithlab/fit/diffuse_models.hpp -- the built-in diffuse BRDFs the fitter fits and compares, each one file in
/// fit/diffuse/ (the model as a free function of its own physical parameters, with its source; its entry in the
/// fitter's one shape, a DiffuseModel; its GLSL), and the registry that lists them.
///
/// The functions allocate nothing and never throw; for z > 0 and alpha in (0, 1] none returns NaN (conventions:
/// fit/diffuse_model.hpp).
#pragma once

#include <string_view>
#include <vector>

#include "smithlab/fit/diffuse/chan_2018.hpp"
#include "smithlab/fit/diffuse/disney.hpp"
#include "smithlab/fit/diffuse/eon.hpp"
#include "smithlab/fit/diffuse/fujii.hpp"
#include "smithlab/fit/diffuse/hammon_2017.hpp"
#include "smithlab/fit/diffuse/lambert.hpp"
#include "smithlab/fit/diffuse/oren_nayar.hpp"
#include "smithlab/fit/diffuse/oren_nayar_qualitative.hpp"
#include "smithlab/fit/diffuse/smithlab_2026.hpp"
#include "smithlab/fit/diffuse_model.hpp"
#include "smithlab/fit/diffuse_registry.hpp"

namespace smithlab::fit {

/// Adds the built-in models, in this order: lambert, disney, oren-nayar (sigma = s alpha, s free, published 0.5:
/// Hammon's comparison), oren-nayar-sqrt2 (sigma = alpha/sqrt(2)), oren-nayar-qualitative (sigma = 0.5 alpha), fujii
/// (sigma = s alpha, s free, start 1), eon (r = clamp(c alpha, 0, 1), c free, start 1), chan-2018 (retro weight 1),
/// hammon-2017, hammon-2017-linear (rough_a, rough_b, rough_c, smooth, multi free), smithlab-2026 (Hammon's constants
/// and p, q, u free; no baseline of its own).
void register_core_diffuse_models(DiffuseRegistry& registry);
/// A registry of the built-in models: the command line's, and the start of a program's own.
DiffuseRegistry builtin_diffuse_registry();

/// The built-in models, made once (builtin_diffuse_registry's list).
const std::vector<DiffuseModel>& diffuse_models();
/// The built-in model named `name`; input_error naming it and listing the known names otherwise.
const DiffuseModel& find_diffuse_model(std::string_view name);

}  // namespace smithlab::fit
