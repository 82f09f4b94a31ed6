// <smithlab/smithlab.hpp> -- the public API in one include: core (any NDF) and the GTR family.
#pragma once

#include "smithlab/any_ndf.hpp"
#include "smithlab/checks.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/ndfs.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/smith.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/variants.hpp"
#include "smithlab/gtr/closed_forms.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/gtr/interpolants.hpp"
#include "smithlab/gtr/registry.hpp"
#include "smithlab/gtr/spline.hpp"
