"""smithlab: Smith masking-shadowing, normal sampling, path tracing and diffuse fitting for any isotropic
microfacet NDF, from Python and NumPy.

Conventions: mu = cot(theta) of a direction (mu = 0 grazing, inf the normal, mu < 0 below the surface); angles
given as theta_* are in degrees; every function takes NumPy arrays or scalars and broadcasts them, computing in
float64. Bad input raises ValueError naming the item.
"""
from ._ndf import Ndf, family_G1, list, methods, ndf, sample, samplers, tabulated
from ._walk import *  # noqa: F401,F403

__all__ = ["Ndf", "family_G1", "list", "methods", "ndf", "sample", "samplers", "tabulated"]
