# Type stub of smithlab._walk (experiments/python/walk.cpp, fit.cpp): the microsurface walk and the fitter's pieces.
# Angle arguments are degrees; array arguments take anything NumPy reads as numbers and broadcast against each other.
import builtins
import os
from typing import Any

import numpy as np
import numpy.typing as npt

from ._ndf import Ndf

_Values = npt.ArrayLike
_Result = np.ndarray | float

def materials() -> builtins.list[tuple[str, str]]: ...
def trace(ndf: Ndf, material: str = "mirror", theta_i: float = 45.0, phi_i: float = 0.0, walks: int = 1000000,
          seed: int = 1, threads: int = 0, max_order: int = 0, downward: str = "smith",
          hit_normal: str = "visible", max_walks: float = 1e11) -> dict[str, Any]: ...
def brdf(ndf: Ndf, material: str, theta_i: _Values, phi_i: _Values, theta_o: _Values, phi_o: _Values,
         walks: int = 1000000, seed: int = 1, threads: int = 0, downward: str = "smith",
         estimator: str = "next_event", max_walks: float = 1e11) -> dict[str, _Result]: ...
def diffuse_models() -> builtins.list[dict[str, Any]]: ...
def diffuse_f(model: str, theta_i: _Values, theta_o: _Values, phi: _Values, alpha: _Values, albedo: _Values,
              constants: npt.ArrayLike | None = None) -> _Result: ...
def read_fit(directory: str | os.PathLike[str], *,
             stderr: bool = False) -> dict[str, dict[str, dict[str, float]]]: ...
def compensation(ndf: Ndf, cosines: int = 48, g2: str = "height-correlated") -> dict[str, np.ndarray | float]: ...
