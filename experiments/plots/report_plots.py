#!/usr/bin/python3
"""Draws the figures of `smithlab report` from the CSV files it wrote: report_plots.py DIR.

Needs Debian's python3-matplotlib (installed by .ci/deps). Each figure is drawn only if its data is there, i.e. only
if the scene asked for it.
"""
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_common import num, rows  # noqa: E402


def pareto(d):
    table = [r for r in rows(os.path.join(d, "variants.csv")) if r["points"] != "0"]
    table.sort(key=lambda r: num(r["ns_per_eval"]))
    colors = {"q1d": "tab:blue", "q2d": "tab:cyan", "interp": "tab:orange", "dimov": "tab:red"}
    fig, axes = plt.subplots(1, 2, figsize=(16, 6.5))
    for ax, key, label in ((axes[0], "max_rel_dLambda", "max relative error of Lambda"),
                           (axes[1], "max_abs_dG1", "max |dG1|")):
        top = 1e3 if key == "max_rel_dLambda" else 2.0
        for i, r in enumerate(table, 1):
            x, y = num(r["ns_per_eval"]), num(r[key])
            clipped = not (y <= top)
            y = top if clipped else max(y, 1e-17)
            ax.scatter([x], [y], marker="^" if clipped else "o", s=30,
                       color=colors.get(r["variant"].split("-")[0], "tab:green"))
            ax.annotate(str(i), (x, y), fontsize=7, xytext=(3, 3 if i % 2 else -9), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("ns per evaluation (Google Benchmark, one core)")
        ax.set_ylabel(label + " (triangles: off the scale or infinite)")
        ax.grid(True, which="both", alpha=0.3)
    key_text = "\n".join(f"{i:2d}  {r['variant']}" for i, r in enumerate(table, 1))
    fig.text(0.84, 0.5, key_text, fontsize=7, family="monospace", va="center", ha="left")
    fig.suptitle("G1 variants: error against run time (numbers: cheapest first)")
    fig.tight_layout(rect=(0, 0, 0.83, 1))
    fig.savefig(os.path.join(d, "pareto.png"), dpi=110)


def log_edges(centers):
    """Cell edges between log-spaced centers (geometric midpoints), extended by half a step at both ends."""
    c = np.log(np.array(centers))
    if len(c) == 1:
        return np.exp(np.array([c[0] - 0.5, c[0] + 0.5]))
    mid = (c[1:] + c[:-1]) / 2
    return np.exp(np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]]))


def error_maps(d):
    pdir = os.path.join(d, "points")
    names = sorted(f[:-4] for f in os.listdir(pdir) if f.endswith(".csv"))
    cols = 5
    nrows = (len(names) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(3.2 * cols, 2.8 * nrows), squeeze=False)
    norm = LogNorm(vmin=1e-16, vmax=1.0)
    for ax, name in zip(axes.flat, names):
        worst = defaultdict(float)
        for r in rows(os.path.join(pdir, name + ".csv")):
            key = (num(r["alpha"]), num(r["mu"]))
            worst[key] = max(worst[key], num(r["abs_dG1"]))
        alphas = sorted({k[0] for k in worst})
        mus = sorted({k[1] for k in worst})
        Z = np.array([[max(worst.get((a, m), 0.0), 1e-16) for a in alphas] for m in mus])
        im = ax.pcolormesh(log_edges(alphas), log_edges(mus), Z, norm=norm, cmap="magma", shading="flat")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(name, fontsize=8)
        ax.tick_params(labelsize=6)
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    fig.supxlabel("alpha")
    fig.supylabel("mu = cot(theta)")
    fig.colorbar(im, ax=axes, shrink=0.6, label="|dG1|, worst over gamma")
    fig.savefig(os.path.join(d, "error_maps.png"), dpi=100)


def dimov_heightfields(d):
    data = defaultdict(dict)
    for r in rows(os.path.join(d, "dimov", "heightfields.csv")):
        data[int(r["gamma"])][(num(r["alpha"]), num(r["mu"]))] = num(r["g1"])
    fig = plt.figure(figsize=(8, 6.5))
    ax = fig.add_subplot(projection="3d")
    colors = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]
    for g, pts in sorted(data.items()):
        alphas = sorted({k[0] for k in pts})
        mus = sorted({k[1] for k in pts})
        X, Y = np.meshgrid(alphas, mus)
        Z = np.array([[pts[(a, m)] for a in alphas] for m in mus])
        ax.plot_wireframe(X, Y, Z, color=colors[g], linewidth=0.4, rstride=4, cstride=4, label=f"gamma = {g}")
    ax.set_xlabel("alpha")
    ax.set_ylabel("mu")
    ax.set_zlabel("G1")
    ax.legend(fontsize=8)
    ax.set_title("Dimov 2015 sec. 4, reproduced: G1 for gamma = 0..4")
    fig.savefig(os.path.join(d, "dimov_heightfields.png"), dpi=110)


def dimov_gamma4_vs_10(d):
    pts = {(num(r["alpha"]), num(r["mu"])): num(r["abs_diff"]) for r in rows(os.path.join(d, "dimov", "gamma4_vs_10.csv"))}
    alphas = sorted({k[0] for k in pts})
    mus = sorted({k[1] for k in pts})
    fig = plt.figure(figsize=(8, 6.5))
    ax = fig.add_subplot(projection="3d")
    X, Y = np.meshgrid(alphas, mus)
    Z = np.array([[10 * pts[(a, m)] for a in alphas] for m in mus])
    ax.plot_surface(X, Y, Z, cmap="viridis", linewidth=0)
    ax.set_xlabel("alpha")
    ax.set_ylabel("mu")
    ax.set_zlabel("10 |G1(4) - G1(10)|")
    ax.set_title("Dimov 2015 sec. 6, reproduced (scaled 10x as published)")
    fig.savefig(os.path.join(d, "gamma4_vs_10.png"), dpi=110)


def sampling_efficiency(d):
    table = rows(os.path.join(d, "sampling.csv"))
    families = sorted({r["family"] for r in table})
    strategies = ["cosine", "dcos", "vndf"]
    labels = {"cosine": "cosine hemisphere", "dcos": "D cos normals", "vndf": "visible normals"}
    colors = {"cosine": "tab:gray", "dcos": "tab:blue", "vndf": "tab:red"}
    styles = {f: s for f, s in zip(families, ["-", "--", ":", "-."])}
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for fam in families:
        for st in strategies:
            pts = sorted((num(r["alpha"]), num(r["variance"]), num(r["efficiency"]))
                         for r in table if r["family"] == fam and r["strategy"] == st)
            if not pts:
                continue
            a, var, eff = zip(*pts)
            kw = dict(color=colors[st], linestyle=styles[fam], marker="o", ms=3, label=f"{fam}: {labels[st]}")
            axes[0].plot(a, [max(v, 1e-12) for v in var], **kw)  # a zero variance is drawn at 1e-12
            axes[1].plot(a, eff, **kw)
    for ax, yl in ((axes[0], "variance of one sample (zero drawn at 1e-12)"),
                   (axes[1], "efficiency 1 / (variance x seconds per sample)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("alpha")
        ax.set_ylabel(yl)
        ax.grid(True, which="both", alpha=0.3)
        ax.invert_xaxis()
    axes[1].legend(fontsize=8)
    fig.suptitle("Directional albedo of a white conductor: the cost of a sampling strategy as alpha -> 0")
    fig.tight_layout()
    fig.savefig(os.path.join(d, "sampling_efficiency.png"), dpi=110)


def walk_albedo(d):
    """Albedo by scattering order against alpha: one panel per theta_i x NDF x material, the orders stacked (they sum
    to the albedo of all orders), and a last column with the energy single scattering loses (orders 2+)."""
    table = rows(os.path.join(d, "walk_albedo.csv"))
    label = {}
    for r in table:
        label[r["ndf"]] = r["label"]
    pairs = list(dict.fromkeys((label[r["ndf"]], r["material"]) for r in table))
    thetas = sorted({num(r["theta_i"]) for r in table})
    value = {(label[r["ndf"]], r["material"], num(r["theta_i"]), r["order"]): [] for r in table}
    for r in table:
        value[(label[r["ndf"]], r["material"], num(r["theta_i"]), r["order"])].append(
            (num(r["alpha"]), num(r["albedo"]), num(r["stderr"])))
    alphas = sorted({num(r["alpha"]) for r in table})
    log_x = len(alphas) > 1 and alphas[-1] / alphas[0] > 20
    orders = ["1", "2", "3", "4+"]
    colors = {"1": "tab:blue", "2": "tab:orange", "3": "tab:green", "4+": "tab:red"}
    cols = len(pairs) + 1
    fig, axes = plt.subplots(len(thetas), cols, figsize=(3.3 * cols, 3.0 * len(thetas) + 0.6), squeeze=False)
    for i, theta in enumerate(thetas):
        for j, (ndf, material) in enumerate(pairs):
            ax = axes[i][j]
            series = [sorted(value.get((ndf, material, theta, o), [])) for o in orders]
            if not series[0]:
                ax.axis("off")
                continue
            a = [p[0] for p in series[0]]
            ax.stackplot(a, *[[p[1] for p in s] for s in series], labels=[f"order {o}" for o in orders],
                         colors=[colors[o] for o in orders], alpha=0.8)
            total = sorted(value[(ndf, material, theta, "all")])
            ax.plot([p[0] for p in total], [p[1] for p in total], "k--", lw=1, label="all orders")
            ax.set_ylim(0, 1.05)
            ax.set_title(f"{ndf}, {material}, theta_i {theta:g}", fontsize=8)
            ax.set_xlabel("alpha", fontsize=8)
            ax.tick_params(labelsize=7)
            if log_x:
                ax.set_xscale("log")
            if j == 0:
                ax.set_ylabel("albedo by scattering order", fontsize=8)
        ax = axes[i][-1]
        for ndf, material in pairs:
            pts = sorted(value.get((ndf, material, theta, "2+"), []))
            if pts:
                ax.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=[p[2] for p in pts], marker="o", ms=3,
                            capsize=2, label=f"{ndf}, {material}")
        ax.set_title(f"lost by single scattering (orders 2+), theta_i {theta:g}", fontsize=8)
        ax.set_xlabel("alpha", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, alpha=0.3)
        if log_x:
            ax.set_xscale("log")
        ax.legend(fontsize=6)
    axes[0][0].legend(fontsize=6, loc="lower left")
    fig.suptitle("Smith microsurface, path-traced: albedo by scattering order, and the energy single scattering loses")
    fig.tight_layout()
    fig.savefig(os.path.join(d, "walk_albedo.png"), dpi=100)


def main():
    d = sys.argv[1]
    drawn = []
    if os.path.isdir(os.path.join(d, "points")):
        pareto(d)
        error_maps(d)
        drawn += ["pareto.png", "error_maps.png"]
    if os.path.exists(os.path.join(d, "dimov", "heightfields.csv")):
        dimov_heightfields(d)
        drawn.append("dimov_heightfields.png")
    if os.path.exists(os.path.join(d, "dimov", "gamma4_vs_10.csv")):
        dimov_gamma4_vs_10(d)
        drawn.append("gamma4_vs_10.png")
    if os.path.exists(os.path.join(d, "sampling.csv")):
        sampling_efficiency(d)
        drawn.append("sampling_efficiency.png")
    if os.path.exists(os.path.join(d, "walk_albedo.csv")):
        walk_albedo(d)
        drawn.append("walk_albedo.png")
    print("report_plots: drew " + ", ".join(drawn), file=sys.stderr)


if __name__ == "__main__":
    main()
