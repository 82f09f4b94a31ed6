/// @file
/// <smithlab/gtr.hpp> -- the whole API in one include: the engine (<smithlab/smithlab.hpp>) and the GTR family
/// (gtr/, CMake target smithlab::gtr): its D, closed forms, interpolants, Dimov's spline, the family evaluator, and the
/// registry of every built-in NDF (builtin_registry).
#pragma once

#include "smithlab/gtr/closed_forms.hpp"
#include "smithlab/gtr/family.hpp"
#include "smithlab/gtr/family_stream.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/gtr/interpolants.hpp"
#include "smithlab/gtr/registry.hpp"
#include "smithlab/gtr/spline.hpp"
#include "smithlab/smithlab.hpp"
