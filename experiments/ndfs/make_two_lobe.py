#!/usr/bin/python3
"""Writes two_lobe.csv beside this script (or to the path given): make_two_lobe.py [OUT.csv].

A measured-looking NDF that no analytic family of smithlab fits: a normalized mixture of a sharp GGX lobe and a broad
Beckmann lobe,
    D = 0.3 D_GGX(alpha 0.08) + 0.7 D_Beckmann(alpha 0.45)          (Walter et al. 2007, eq. 33 and 25),
normalized because each lobe is (integral of D cos over the hemisphere = 1) and the weights sum to 1. Sampled at 120
irregular angles over [0, 88] degrees (a uniform step, each inner angle moved by up to +-35 % of it), each D times
exp(0.01 z), z standard normal: 1 % multiplicative noise. Deterministic: numpy's legacy RandomState (its streams
are frozen across numpy versions) with a fixed seed. Its Smith Lambda is the mixture's, 0.3 Lambda_GGX + 0.7
Lambda_Beckmann (Lambda is linear in the slope density, Walter 2007 eq. 48), up to the noise: tests/test_tabulated.cpp
checks that (within 4e-3 from mu = 0.01 to 100), and that smithlab::read_tabulated_ndf reads it without normalize (its
projected area, with the reader's interpolation, is 0.998). Needs python3 and numpy only.
"""
import math
import os
import sys

import numpy as np

SEED = 20240611
ROWS = 120
THETA_MAX_DEG = 88.0
NOISE = 0.01
W_GGX, A_GGX = 0.3, 0.08
W_BECKMANN, A_BECKMANN = 0.7, 0.45


def d_ggx(alpha, c):
    """Walter 2007 eq. 33, with sin^2 = (1 - c)(1 + c)."""
    s = (1.0 - c) * (1.0 + c) + alpha * alpha * c * c
    return alpha * alpha / (math.pi * s * s)


def d_beckmann(alpha, c):
    """Walter 2007 eq. 25: exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4)."""
    tan2 = (1.0 - c) * (1.0 + c) / (c * c)
    return np.exp(-tan2 / (alpha * alpha)) / (math.pi * alpha * alpha * c ** 4)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "two_lobe.csv")
    rng = np.random.RandomState(SEED)
    step = THETA_MAX_DEG / (ROWS - 1)
    jitter = rng.uniform(-0.35, 0.35, ROWS) * step
    jitter[0] = jitter[-1] = 0.0
    theta = np.arange(ROWS) * step + jitter
    theta[-1] = THETA_MAX_DEG
    c = np.cos(np.radians(theta))
    d = W_GGX * d_ggx(A_GGX, c) + W_BECKMANN * d_beckmann(A_BECKMANN, c)
    d *= np.exp(NOISE * rng.standard_normal(ROWS))
    with open(out, "w", newline="\n") as f:
        f.write("# two_lobe: D = 0.3 GGX(alpha 0.08) + 0.7 Beckmann(alpha 0.45), normalized, at 120 irregular angles "
                "over [0, 88] degrees, 1 %% multiplicative noise (seed %d); written by make_two_lobe.py\n" % SEED)
        f.write("theta_deg,D\n")
        for t, v in zip(theta, d):
            f.write("%.6f,%.10g\n" % (t, v))


if __name__ == "__main__":
    main()
