#!/usr/bin/python3
"""Draws the figures of `smithlab report` from the CSV files it wrote: report_plots.py DIR.

Needs Debian's python3-matplotlib (installed by .ci/deps). Each figure is drawn only if its data is there, i.e. only
if the scene asked for it. Columns are read by name: a CSV may carry more columns than the ones read here.
"""
import math
import os
import re
import sys
from collections import defaultdict

# plot_common first: it says what is missing when matplotlib is (and selects the Agg backend).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_common import num, place_labels, rows, save, use_style  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import LogLocator, NullFormatter  # noqa: E402
import numpy as np  # noqa: E402

# ---------------------------------------------------------------------------------------------------------------------
# pareto.png: each G1 variant's worst error against its cost

# A variant's kind, by the start of its name: (prefix, colour, legend text). The first matching prefix wins.
VARIANT_KINDS = (
    ("closed-form", "black", "closed form of the NDF"),
    ("q1d-boost", "tab:blue", "1D quadrature, Boost tanh-sinh (tolerance 1e-4 ... 1e-12)"),
    ("q1d-gsl", "tab:purple", "1D quadrature, GSL QAG (tolerance 1e-4 ... 1e-12)"),
    ("interp", "tab:orange", "spline in gamma through the closed forms"),
    ("dimov", "tab:red", "Dimov 2015 spline in gamma"),
    ("table", "tab:green", "table or patches built for the NDF"),
    ("family", "tab:green", "table or patches built for the NDF"),
    ("", "tab:brown", "published approximation (one NDF)"),
)


def variant_kind(name):
    """(colour, legend text) of a variant by its name's prefix."""
    for prefix, color, text in VARIANT_KINDS:
        if name.startswith(prefix):
            return color, text
    return "tab:gray", "other"


def tolerance_series(table, key, top):
    """{name without tolerance: [(ns, error)] from the loosest tolerance to the tightest} for the variants named
    with a trailing tolerance (q1d-gsl-1e-8), finite errors only."""
    out = defaultdict(list)
    for r in sorted(table, key=lambda r: variant_order(r["variant"])):
        prefix, tol = variant_order(r["variant"])
        y = num(r[key])
        if tol != 0.0 and 0 < y <= top:
            out[prefix].append((num(r["ns_per_eval"]), y))
    return out


def pareto_panel(ax, table, key, label, top):
    """One panel of pareto.png: each variant at (ns per evaluation, its error key), numbered; an error above top (or
    infinite) as a triangle up at top, an error of exactly 0 as a triangle down at the bottom edge."""
    finite = [num(r[key]) for r in table if 0 < num(r[key]) <= top]
    bottom = min(finite, default=top * 1e-3) / 10
    xy, texts, colors = [], [], []
    for i, r in enumerate(table, 1):
        x, y = num(r["ns_per_eval"]), num(r[key])
        color = variant_kind(r["variant"])[0]
        marker = "o"
        if not y <= top:
            y, marker = top, "^"
        elif y <= 0.0:
            y, marker = bottom, "v"
        ax.scatter([x], [y], marker=marker, s=36, color=color, zorder=3)
        xy.append((x, y))
        texts.append(str(i))
        colors.append(color)
    for prefix, pts in tolerance_series(table, key, top).items():  # one quadrature, tolerance by tolerance
        ax.plot([p[0] for p in pts], [p[1] for p in pts], color=variant_kind(prefix)[0], lw=0.8, alpha=0.6)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(bottom / 2, top * 4)
    ax.axhline(top, color="0.6", lw=0.6, ls=":")
    ax.set_xlabel("cost: ns per evaluation (Google Benchmark, one core)")
    ax.set_ylabel(label)
    ax.grid(True, which="major", alpha=0.3)
    place_labels(ax, xy, texts, fontsize=8, colors=colors)


def pareto(d):
    table = [r for r in rows(os.path.join(d, "variants.csv")) if r["points"] != "0"]
    table.sort(key=lambda r: num(r["ns_per_eval"]))
    fig = plt.figure(figsize=(12, 5.6))
    grid = fig.add_gridspec(1, 3, width_ratios=(1, 1, 0.62), wspace=0.28, left=0.07, right=0.99, top=0.9,
                            bottom=0.27)
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])]
    pareto_panel(axes[0], table, "max_rel_dLambda", "worst relative error of Λ", 1e3)
    pareto_panel(axes[1], table, "max_abs_dG1", "worst |ΔG1|", 2.0)
    key = fig.add_subplot(grid[0, 2])
    key.axis("off")
    for i, r in enumerate(table, 1):
        key.text(-0.05, 1 - (i - 0.5) / len(table), f"{i:2d} {r['variant']}", fontsize=8, family="monospace",
                 color=variant_kind(r["variant"])[0], va="center", transform=key.transAxes)
    kinds = list(dict.fromkeys(variant_kind(r["variant"]) for r in table))
    handles = [Line2D([], [], ls="", marker="o", color=c, label=t) for c, t in kinds]
    handles += [Line2D([], [], ls="", marker="^", color="0.3", label="off the scale or infinite (drawn at the top)"),
                Line2D([], [], ls="", marker="v", color="0.3", label="exactly 0 (drawn at the bottom)")]
    fig.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.07, 0.0), ncol=2, frameon=False)
    fig.suptitle("G1 variants: worst error over the grid against cost (numbers: the report's table, cheapest first)")
    save(fig, os.path.join(d, "pareto.png"))


# ---------------------------------------------------------------------------------------------------------------------
# error_maps.png: where each variant fails, over (alpha, mu)

ERROR_FLOOR = 1e-16  # errors below it (exact 0 included) take the colour map's lowest colour


def log_edges(centers):
    """Cell edges between log-spaced centers (geometric midpoints), extended by half a step at both ends."""
    c = np.log(np.array(centers))
    if len(c) == 1:
        return np.exp(np.array([c[0] - 0.5, c[0] + 0.5]))
    mid = (c[1:] + c[:-1]) / 2
    return np.exp(np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]]))


def two_lines(name, width=20):
    """A long variant name broken at the hyphen nearest its middle."""
    if len(name) <= width or "-" not in name:
        return name
    cuts = [i for i, ch in enumerate(name) if ch == "-"]
    cut = min(cuts, key=lambda i: abs(i - len(name) / 2))
    return name[:cut + 1] + "\n" + name[cut + 1:]


def worst_grid(path):
    """(alphas, mus, Z): the worst |dG1| over gamma at each (alpha, mu) of one variant's points; NaN where none."""
    worst = {}
    for r in rows(path):
        key = (num(r["alpha"]), num(r["mu"]))
        worst[key] = max(worst.get(key, 0.0), num(r["abs_dG1"]))
    alphas = sorted({k[0] for k in worst})
    mus = sorted({k[1] for k in worst})
    Z = np.array([[worst.get((a, m), np.nan) for a in alphas] for m in mus])
    return alphas, mus, Z


def variant_order(name):
    """Sorts variant names alphabetically, but a trailing tolerance (q1d-gsl-1e-10) by its value, loosest first."""
    m = re.fullmatch(r"(.*)-(\d+(?:\.\d+)?e-\d+)", name)
    return (m.group(1), -float(m.group(2))) if m else (name, 0.0)


def error_maps(d):
    pdir = os.path.join(d, "points")
    names = sorted((f[:-4] for f in os.listdir(pdir) if f.endswith(".csv")), key=variant_order)
    cols = min(6, len(names))
    nrows = (len(names) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(1.75 * cols + 1.5, 1.95 * nrows + 1.0), squeeze=False,
                             sharex=True, sharey=True)
    fig.subplots_adjust(left=0.09, right=0.86, top=1 - 0.8 / fig.get_figheight(),
                        bottom=0.65 / fig.get_figheight(), wspace=0.2, hspace=0.45)
    norm = LogNorm(vmin=ERROR_FLOOR, vmax=1.0)
    cmap = plt.get_cmap("magma").copy()
    cmap.set_bad("0.85")
    any_missing = False
    for ax, name in zip(axes.flat, names):
        alphas, mus, Z = worst_grid(os.path.join(pdir, name + ".csv"))
        any_missing |= bool(np.isnan(Z).any())
        im = ax.pcolormesh(log_edges(alphas), log_edges(mus), np.ma.masked_invalid(np.maximum(Z, ERROR_FLOOR)),
                           norm=norm, cmap=cmap, shading="flat")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_major_locator(LogLocator(base=100.0, numticks=10))
        ax.yaxis.set_major_locator(LogLocator(base=100.0, numticks=10))
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_minor_formatter(NullFormatter())
        ax.set_title(two_lines(name), fontsize=8.5)
        ax.tick_params(labelsize=8)
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    fig.supxlabel("α (roughness)", y=0.02)
    fig.supylabel("μ = cot θ (θ: angle from the normal)", x=0.02)
    cax = fig.add_axes((0.885, 0.2, 0.018, 0.6))
    cbar = fig.colorbar(im, cax=cax, extend="min")
    cbar.set_label(f"|ΔG1|, worst over γ (below {ERROR_FLOOR:g}, exact 0 too: the darkest colour)")
    title = "Where each G1 variant fails: |ΔG1| against the reference over (α, μ)"
    if any_missing:
        title += " (grey: not evaluated)"
    fig.suptitle(title)
    save(fig, os.path.join(d, "error_maps.png"), dpi=120)


# ---------------------------------------------------------------------------------------------------------------------
# dimov_heightfields.png and gamma4_vs_10.png: Dimov 2015, sec. 4 and 6

def dimov_heightfields(d):
    """G1 against mu at the smallest, a middle and the largest alpha of the grid, a line per gamma (overlaid
    surfaces hide one another), and where gamma matters: max - min over gamma of G1 over (alpha, mu)."""
    data = defaultdict(dict)
    for r in rows(os.path.join(d, "dimov", "heightfields.csv")):
        data[num(r["gamma"])][(num(r["alpha"]), num(r["mu"]))] = num(r["g1"])
    gammas = sorted(data)
    alphas = sorted({k[0] for pts in data.values() for k in pts})
    mus = sorted({k[1] for pts in data.values() for k in pts})
    shown = list(dict.fromkeys([alphas[0], alphas[len(alphas) // 2], alphas[-1]]))
    fig, axes = plt.subplots(1, len(shown) + 1, figsize=(3.1 * (len(shown) + 1), 3.6),
                             gridspec_kw={"width_ratios": [1] * len(shown) + [1.25]})
    cmap = plt.get_cmap("viridis")
    for ax, a in zip(axes, shown):
        for i, g in enumerate(gammas):
            ax.plot(mus, [data[g].get((a, m), np.nan) for m in mus], color=cmap(i / max(1, len(gammas) - 1)),
                    lw=1.3, label=f"γ = {g:g}")
        ax.set_title(f"α = {a:g}")
        ax.set_xlabel("μ = cot θ")
        ax.set_ylim(0, 1.02)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("G1")
    axes[0].legend(loc="lower right")
    spread = np.array([[max(data[g].get((a, m), np.nan) for g in gammas) - min(data[g].get((a, m), np.nan)
                                                                                for g in gammas)
                        for a in alphas] for m in mus])
    ax = axes[-1]
    im = ax.pcolormesh(alphas, mus, spread, cmap="viridis", shading="nearest")
    ax.set_xlabel("α")
    ax.set_ylabel("μ = cot θ")
    ax.set_title(f"spread over γ = {gammas[0]:g}..{gammas[-1]:g}")
    fig.colorbar(im, ax=ax).set_label("max − min of G1 over γ")
    fig.suptitle(f"Dimov 2015 sec. 4, reproduced: G1 of the GTR family for γ = {gammas[0]:g}..{gammas[-1]:g}")
    fig.tight_layout()
    save(fig, os.path.join(d, "dimov_heightfields.png"))


def dimov_gamma4_vs_10(d):
    pts = {(num(r["alpha"]), num(r["mu"])): num(r["abs_diff"]) for r in rows(os.path.join(d, "dimov", "gamma4_vs_10.csv"))}
    alphas = sorted({k[0] for k in pts})
    mus = sorted({k[1] for k in pts})
    fig = plt.figure(figsize=(7, 5.8))
    ax = fig.add_subplot(projection="3d")
    X, Y = np.meshgrid(alphas, mus)
    Z = np.array([[10 * pts[(a, m)] for a in alphas] for m in mus])
    ax.plot_surface(X, Y, Z, cmap="viridis", linewidth=0)
    ax.set_xlabel("α")
    ax.set_ylabel("μ = cot θ")
    ax.set_zlabel("10 |G1(γ=4) − G1(γ=10)|")
    ax.set_box_aspect(None, zoom=0.88)
    fig.subplots_adjust(left=0.0, right=0.95, bottom=0.02, top=0.98)
    fig.suptitle("Dimov 2015 sec. 6, reproduced (scaled 10x as published)", y=0.95)
    save(fig, os.path.join(d, "gamma4_vs_10.png"))


# ---------------------------------------------------------------------------------------------------------------------
# sampling_efficiency.png: the variance of each sampling strategy, and its efficiency

SAMPLING_STRATEGIES = {"cosine": ("cosine hemisphere", "tab:gray"), "dcos": ("D cos normals", "tab:blue"),
                       "vndf": ("visible normals", "tab:red")}
UNCONVERGED_SIGMAS = 4.0  # a mean further than this many combined standard errors from the best estimate


def mark_unconverged(table):
    """For each row, whether its mean disagrees with the most precise other estimate of the same (family, alpha) by
    more than UNCONVERGED_SIGMAS combined standard errors: the three strategies estimate one albedo, so such an
    estimate has not seen the samples that carry its integral (and its sample variance is too small as well)."""
    by_cell = defaultdict(list)
    for r in table:
        by_cell[(r["family"], num(r["alpha"]))].append(r)
    flags = {}
    for cell in by_cell.values():
        for r in cell:
            others = [o for o in cell if o is not r]
            if not others:
                flags[id(r)] = False
                continue
            ref = min(others, key=lambda o: num(o["stderr"]))
            se = math.hypot(num(r["stderr"]), num(ref["stderr"]))
            gap = abs(num(r["mean"]) - num(ref["mean"]))
            flags[id(r)] = gap > UNCONVERGED_SIGMAS * se if se > 0 else gap > 0
    return flags


def sampling_series(table, flags, fam, st, key):
    """(alpha, value, status) of one family and strategy, by alpha; status: 'ok', 'unconverged', 'zero' (a sample
    variance of 0: no sample differed), 'inf' (an infinite efficiency, from a zero variance)."""
    out = []
    for r in table:
        if r["family"] != fam or r["strategy"] != st:
            continue
        v = num(r[key])
        status = "unconverged" if flags[id(r)] else "inf" if math.isinf(v) else "zero" if v == 0 else "ok"
        out.append((num(r["alpha"]), v, status))
    return sorted(out)


def sampling_panel(ax, table, flags, families, key, styles):
    """Draws one quantity against alpha: lines through the valid estimates only (broken at the others); unconverged
    estimates hollow, zero variances at the bottom edge, infinite efficiencies at the top edge."""
    edge = ax.get_xaxis_transform()  # x in data, y in axes fraction
    for fam in families:
        for st, (_, color) in SAMPLING_STRATEGIES.items():
            pts = sampling_series(table, flags, fam, st, key)
            if not pts:
                continue
            a = [p[0] for p in pts]
            ax.plot(a, [p[1] if p[2] == "ok" else np.nan for p in pts], color=color, ls=styles[fam], marker="o",
                    ms=3.5)
            bad = [p for p in pts if p[2] == "unconverged"]
            ax.plot([p[0] for p in bad], [p[1] for p in bad], ls="", marker="o", ms=8, mfc="none", mec=color, mew=1.5)
            for status, y, marker in (("zero", 0.02, "v"), ("inf", 0.98, "^")):
                at = [p[0] for p in pts if p[2] == status]
                ax.plot(at, [y] * len(at), ls="", marker=marker, ms=7, color=color, transform=edge, clip_on=False)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("α (roughness)")
    ax.grid(True, which="major", alpha=0.3)
    ax.invert_xaxis()


def sampling_efficiency(d):
    table = rows(os.path.join(d, "sampling.csv"))
    flags = mark_unconverged(table)
    families = sorted({r["family"] for r in table})
    styles = {f: s for f, s in zip(families, ["-", "--", ":", "-."])}
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.6))
    fig.subplots_adjust(left=0.08, right=0.98, top=0.91, bottom=0.3, wspace=0.25)
    sampling_panel(axes[0], table, flags, families, "variance", styles)
    sampling_panel(axes[1], table, flags, families, "efficiency", styles)
    axes[0].set_ylabel("variance of one sample")
    axes[1].set_ylabel("efficiency: 1 / (variance × seconds per sample)")
    handles = [Line2D([], [], color=c, marker="o", ms=3.5, label=t) for t, c in SAMPLING_STRATEGIES.values()]
    handles += [Line2D([], [], color="black", ls=styles[f], label=f) for f in families]
    handles += [Line2D([], [], ls="", label=" ")] * (-len(handles) % 3)  # a column each: strategies, families, marks
    handles += [Line2D([], [], ls="", marker="o", ms=8, mfc="none", mec="black", mew=1.5,
                       label=f"unconverged: mean > {UNCONVERGED_SIGMAS:g} stderr off the best estimate"),
                Line2D([], [], ls="", marker="v", ms=7, color="black", label="sample variance 0 (at the bottom edge)"),
                Line2D([], [], ls="", marker="^", ms=7, color="black", label="efficiency infinite (at the top edge)")]
    fig.legend(handles=handles, loc="lower center", ncol=len(handles) // 3, frameon=False)
    fig.suptitle("Directional albedo of a white conductor: the cost of a sampling strategy as α → 0")
    save(fig, os.path.join(d, "sampling_efficiency.png"))


# ---------------------------------------------------------------------------------------------------------------------
# walk_albedo.png: the path-traced albedo by scattering order

WALK_ORDERS = ("1", "2", "3", "4+")
WALK_ORDER_COLORS = {"1": "tab:blue", "2": "tab:orange", "3": "tab:green", "4+": "tab:red"}
WALK_MATERIAL_STYLES = (("-", "o"), ("--", "s"), (":", "^"), ("-.", "D"))
WALK_NDF_COLORS = ("black", "tab:purple", "tab:brown", "tab:olive", "tab:cyan", "tab:pink", "tab:gray")  # not the
# orders' colours


def walk_table(d):
    """{(label, material, theta_i, order): [(alpha, albedo, stderr)]} and the labels, materials, thetas in order."""
    table = rows(os.path.join(d, "walk_albedo.csv"))
    value = defaultdict(list)
    for r in table:
        value[(r["label"], r["material"], num(r["theta_i"]), r["order"])].append(
            (num(r["alpha"]), num(r["albedo"]), num(r["stderr"])))
    for v in value.values():
        v.sort()
    labels = list(dict.fromkeys(r["label"] for r in table))
    materials = list(dict.fromkeys(r["material"] for r in table))
    thetas = sorted({num(r["theta_i"]) for r in table})
    log_x = len({num(r["alpha"]) for r in table}) > 1 and max(num(r["alpha"]) for r in table) / min(
        num(r["alpha"]) for r in table) > 20
    return value, labels, materials, thetas, log_x


def walk_stack(ax, value, key, log_x):
    """One panel: the albedo of orders 1, 2, 3, 4+ stacked against alpha, and the albedo of all orders dashed."""
    series = [value.get(key + (o,), []) for o in WALK_ORDERS]
    if not series[0]:
        ax.axis("off")
        return
    ax.stackplot([p[0] for p in series[0]], *[[p[1] for p in s] for s in series],
                 colors=[WALK_ORDER_COLORS[o] for o in WALK_ORDERS], alpha=0.85)
    total = value.get(key + ("all",), [])
    ax.plot([p[0] for p in total], [p[1] for p in total], "k--", lw=1)
    ax.set_ylim(0, 1.05)
    if log_x:
        ax.set_xscale("log")


def walk_lost(ax, value, labels, materials, theta, log_x):
    """One panel: orders 2+ (what single scattering loses) against alpha, colour the NDF, line and marker the
    material, with one standard error."""
    for i, label in enumerate(labels):
        for j, material in enumerate(materials):
            pts = value.get((label, material, theta, "2+"), [])
            if not pts:
                continue
            ls, marker = WALK_MATERIAL_STYLES[j % len(WALK_MATERIAL_STYLES)]
            ax.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=[p[2] for p in pts], color=WALK_NDF_COLORS[i % len(WALK_NDF_COLORS)],
                        ls=ls, marker=marker, ms=4, capsize=2)
    ax.set_title(f"lost by single scattering (orders 2+), θ_i = {theta:g}°")
    ax.set_xlabel("α (roughness)")
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    if log_x:
        ax.set_xscale("log")


def walk_legends(fig, labels, materials):
    stack = [plt.Rectangle((0, 0), 1, 1, color=WALK_ORDER_COLORS[o], alpha=0.85) for o in WALK_ORDERS]
    stack.append(Line2D([], [], color="black", ls="--"))
    fig.legend(stack, [f"order {o}" for o in WALK_ORDERS] + ["all orders"], loc="upper center", ncol=5,
               bbox_to_anchor=(0.5, 1 - 0.45 / fig.get_figheight()), frameon=False)
    lost = [Line2D([], [], color=WALK_NDF_COLORS[i % len(WALK_NDF_COLORS)], lw=2) for i in range(len(labels))]
    lost += [Line2D([], [], color="black", ls=WALK_MATERIAL_STYLES[j % 4][0], marker=WALK_MATERIAL_STYLES[j % 4][1],
                    ms=4) for j in range(len(materials))]
    fig.legend(lost, labels + materials, loc="lower center", ncol=min(6, len(lost)), frameon=False)


def walk_albedo(d):
    """Albedo by scattering order against alpha: a row per NDF, a column per theta_i x material, the orders stacked
    (they sum to the albedo of all orders); below, per theta_i, the energy single scattering loses (orders 2+)."""
    value, labels, materials, thetas, log_x = walk_table(d)
    columns = [(t, m) for t in thetas for m in materials]
    fig = plt.figure(figsize=(2.5 * len(columns) + 1.3, 2.0 * len(labels) + 3.9))
    h = fig.get_figheight()
    grid = fig.add_gridspec(len(labels) + 1, len(columns), height_ratios=[1] * len(labels) + [1.45],
                            left=0.1, right=0.98, top=1 - 0.95 / h, bottom=0.95 / h, hspace=0.5, wspace=0.12)
    for i, label in enumerate(labels):
        for j, (theta, material) in enumerate(columns):
            ax = fig.add_subplot(grid[i, j])
            walk_stack(ax, value, (label, material, theta), log_x)
            if i == 0:
                ax.set_title(f"θ_i = {theta:g}°, {material}")
            if j == 0:
                ax.set_ylabel(f"{label}\nalbedo by order")
            else:
                ax.set_yticklabels([])
            if i < len(labels) - 1:
                ax.set_xticklabels([])
            else:
                ax.set_xlabel("α (roughness)")
    span = len(materials)
    for k, theta in enumerate(thetas):
        ax = fig.add_subplot(grid[len(labels), k * span:(k + 1) * span])
        walk_lost(ax, value, labels, materials, theta, log_x)
        if k == 0:
            ax.set_ylabel("albedo of orders 2+")
    walk_legends(fig, labels, materials)
    fig.suptitle("Smith microsurface, path-traced: albedo by scattering order, and the energy single scattering loses")
    save(fig, os.path.join(d, "walk_albedo.png"))


def main():
    d = sys.argv[1]
    use_style()
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
