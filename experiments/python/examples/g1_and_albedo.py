"""smithlab from Python, in cells (`# %%`: run it whole, or cell by cell in an editor that knows them).

Two figures into the output directory (the first argument, default "."):
  g1_gtr.png           Smith's G1 against the angle of the direction, GTR at alpha 0.3, gamma 1, 1.5 and 3
  albedo_by_order.png  the traced albedo of mirror facets on GGX at theta_i 45 degrees by scattering order
                       (1, 2, 3, 4+ facet hits), against alpha: the light single scattering misses grows with roughness

    PYTHONPATH=build/python python3 experiments/python/examples/g1_and_albedo.py out/
"""
# %% Setup: the output directory, a plotting backend that needs no display.
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import smithlab  # noqa: E402

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out.mkdir(parents=True, exist_ok=True)

# %% G1 of GTR against theta: mu = cot(theta), from the normal (mu = inf, G1 = 1) to grazing (mu -> 0, G1 -> 0).
theta = np.linspace(0.0, 90.0, 361)
with np.errstate(divide="ignore"):
    mu = 1.0 / np.tan(np.radians(theta))

fig, ax = plt.subplots(figsize=(6, 4))
for gamma in [1.0, 1.5, 3.0]:
    gtr = smithlab.ndf("gtr", alpha=0.3, gamma=gamma)
    ax.plot(theta, gtr.G1(mu), label=f"gamma = {gamma:g}")
ax.set_xlabel("theta (degrees from the normal)")
ax.set_ylabel("G1")
ax.set_title("Smith G1 of GTR, alpha = 0.3")
ax.set_xlim(0, 90)
ax.set_ylim(0, 1.02)
ax.grid(alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(out / "g1_gtr.png", dpi=150)
plt.close(fig)

# %% The albedo of mirror facets on GGX by scattering order, traced (2e5 walks per alpha).
alphas = np.linspace(0.1, 1.0, 6)
by_order = []
for alpha in alphas:
    r = smithlab.trace(smithlab.ndf("ggx", alpha=alpha), "mirror", theta_i=45.0, walks=200_000, seed=1)
    reflection, every = r["hemispheres"].index("reflection"), r["components"].index("all")
    by_order.append(r["albedo"][reflection, :4, every])  # orders 1, 2, 3, 4+
by_order = np.array(by_order)

fig, ax = plt.subplots(figsize=(6, 4))
for k, name in enumerate(r["orders"][:4]):
    ax.plot(alphas, by_order[:, k], marker="o", label=f"order {name}")
ax.plot(alphas, by_order.sum(axis=1), "k--", label="all (1 for mirrors)")
ax.set_xlabel("GGX alpha")
ax.set_ylabel("albedo")
ax.set_yscale("log", nonpositive="mask")  # an order no walk reached is left out
ax.set_title("Mirror facets, theta_i = 45 degrees: albedo by order")
ax.grid(alpha=0.3, which="both")
ax.legend()
fig.tight_layout()
fig.savefig(out / "albedo_by_order.png", dpi=150)
plt.close(fig)
print(f"wrote {out / 'g1_gtr.png'} and {out / 'albedo_by_order.png'}")
