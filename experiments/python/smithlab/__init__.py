"""smithlab: Smith masking-shadowing, normal sampling, path tracing and diffuse fitting for any isotropic
microfacet NDF, from Python and NumPy.

Conventions: mu = cot(theta) of a direction (mu = 0 grazing, inf the normal, mu < 0 below the surface); angles
named theta_* and phi_* are in degrees. Every function of points takes NumPy arrays or scalars, broadcasts them
against each other and computes in float64 (a scalar in every argument gives a Python float). Bad input raises
ValueError naming the item; no accepted input gives a NaN.
"""
from typing import Any, Callable

import numpy as _np

from ._ndf import Ndf, family_G1, list, methods, ndf, sample, samplers, tabulated
from . import _walk as _walk_module
from ._walk import *  # noqa: F401,F403

__all__ = ["Ndf", "family_G1", "from_function", "list", "methods", "ndf", "sample", "samplers", "tabulated"]
__all__ += sorted(k for k in dir(_walk_module) if not k.startswith("_"))


def from_function(D: "Callable[[Any], Any]", name: str, *, rows: int = 4096, theta_min_deg: float = 1e-3,
                  theta_max_deg: float = 89.99, normalize: bool = False) -> Ndf:
    """An NDF from a Python function D(cos_theta_m), registered as the family `name` (parameter scale).

    D is called once, with a float64 array of cos theta_m, and must return D per steradian of m, normalized so
    that the integral of D cos theta_m over the hemisphere is 1 (normalize=True divides by that area instead of
    refusing one off by more than 1e-2); a function of one float is called row by row instead. The rows are
    theta_m = 0 and `rows` - 1 angles spaced evenly in log theta from theta_min_deg to theta_max_deg (dense at the
    pole, so that a narrow peak is resolved at any roughness), interpolated as smithlab.tabulated does (tabulated.hpp):
    every derived quantity then runs in C++ and never calls back into Python.
    What the sampling leaves (GGX and Beckmann written in Python against their closed forms, 4096 rows, alpha
    1e-3 .. 1, mu in [0.01 alpha, 1000 alpha]): the relative error of Lambda is below 2e-9 for GGX, and below 1e-6
    for Beckmann where Lambda > 1e-8 (its tail falls faster than the interpolation in ln D resolves).
    A name made again (a notebook cell run twice) takes the new table; a built-in name is refused.
    """
    if not (isinstance(rows, int) and rows >= 3):
        raise ValueError(f"from_function '{name}': rows must be an integer >= 3, got {rows!r}")
    if not 0.0 < theta_min_deg < theta_max_deg < 90.0:
        raise ValueError(f"from_function '{name}': need 0 < theta_min_deg < theta_max_deg < 90, got "
                         f"{theta_min_deg!r} and {theta_max_deg!r}")
    theta = _np.concatenate(([0.0], _np.geomspace(theta_min_deg, theta_max_deg, rows - 1)))
    cos_theta = _np.cos(_np.radians(theta))
    try:
        values = _np.asarray(D(cos_theta), dtype=float)
    except (TypeError, ValueError):  # a function of one float ("truth value of an array is ambiguous", ...)
        values = None
    if values is None or values.shape != cos_theta.shape:
        values = _np.array([float(D(float(c))) for c in cos_theta])
    return tabulated(name, theta_deg=theta, D=values, normalize=normalize)
