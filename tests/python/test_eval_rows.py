"""Every Lambda and G1 the module gives agrees with itself, as the command line's rows do (tests/test_eval_rows.cpp):
G1 = 1 / (1 + Lambda) to rounding for every registered NDF's first example x every method of smithlab.methods() x
mu from the smallest subnormal to the largest double; Lambda = 0 only where G1 = 1, Lambda = inf only where 1/G1 - 1
overflows too. Arrays go through the module's broadcasting, one call per (NDF, method)."""
import math
import sys

import numpy as np
import pytest

import smithlab

MU = np.array([5e-324, 1e-300, 1e-100, 1e-12, 1e-4, 0.01, 0.5, 1.0, 10.0, 1e6, 1e100, 1e300, sys.float_info.max])
EPS = sys.float_info.epsilon


def disagreement(lam, g1):
    if math.isnan(lam) or math.isnan(g1):
        return "NaN"
    if not 0.0 <= g1 <= 1.0:
        return "g1 outside [0, 1]"
    if lam < 0.0:
        return "lambda < 0"
    if lam == 0.0:
        return "" if g1 == 1.0 else "lambda = 0 with g1 < 1"
    if lam == math.inf:
        with np.errstate(over="ignore", divide="ignore"):
            return "lambda = inf with 1 / g1 - 1 finite" if np.isfinite(np.float64(1.0) / g1 - 1.0) else ""
    expected = 1.0 / (1.0 + lam)
    return "" if abs(g1 - expected) <= 2.0 * EPS * expected else "g1 != 1 / (1 + lambda)"


SPECS = [family["examples"][0] for family in smithlab.list() if family["examples"]]
# The q2d-* variants are quadrature2d at other tolerances: tests/test_eval_rows.cpp sweeps them.
METHODS = [name for name, _ in smithlab.methods() if not name.startswith("q2d-")]


@pytest.mark.parametrize("spec", SPECS)
def test_every_row_agrees_with_itself(spec):
    n = smithlab.ndf(spec)
    applied = rows = 0
    for method in METHODS:
        try:
            n.Lambda(1.0, method=method)
        except ValueError:
            continue  # a method the NDF lacks (closed, spline, a variant of another family): refused by name
        applied += 1
        # The nested 2D route costs up to seconds a point: at the extremes and one point of each scale.
        grid = MU if method != "quadrature2d" else np.array([5e-324, 0.01, 1.0, 1e6, sys.float_info.max])
        for mu in grid:
            try:
                lam, g1 = n.Lambda(mu, method=method), n.G1(mu, method=method)
            except ValueError:
                continue  # beyond the quadratures' domain, refused by name (docs/accuracy-and-limits.md)
            rows += 1
            assert disagreement(lam, g1) == "", f"{spec} method={method} mu={mu}: lambda {lam}, g1 {g1}"
            assert n.G1(-mu, method=method) == g1
            assert n.Lambda(-mu, method=method) == -1.0 - lam
        # The same through the arrays, where the whole grid is accepted.
        try:
            lam, g1 = n.Lambda(grid, method=method), n.G1(grid, method=method)
        except ValueError:
            continue
        assert all(disagreement(l, g) == "" for l, g in zip(lam, g1))
    assert applied >= 4  # auto, quadrature, quadrature2d, fixed at least
    assert rows >= applied * 5 // 2
