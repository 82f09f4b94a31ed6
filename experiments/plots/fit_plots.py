#!/usr/bin/python3
"""Draws the pictures of `smithlab fit` from the CSV files it wrote into DIR (OUT/pictures): fit_plots.py DIR.

Needs Debian's python3-matplotlib (installed by .ci/deps). experiments/fit/fit_pictures.cpp writes the data:
  ndfs.csv                 ndf,stem,pixels: the NDF families, their file stems, the spheres' diameter
  spheres.csv              ndf,source,alpha,light_deg,albedo,px,py,value: radiance f(l, v) cos theta_l per lit pixel
  slices.csv               ndf,source,alpha,theta_h,theta_d,value,stderr: the BRDF f at phi_d = 90 degrees
  missing.csv              ndf,alpha,theta,albedo,E,E1,missing,stderr: Lambertian facets, 1 - E_1/E
  constants_vs_FAMILY_PARAMETER.csv   ndf,model,parameter,PARAMETER,value,stderr (a family fitted at two values or
                           more of one parameter, e.g. constants_vs_gtr_gamma.csv)
and this script draws spheres_STEM.png, lambert_spheres_STEM.png, slices_STEM.png, missing_STEM.png and
constants_vs_FAMILY_PARAMETER.png. Each figure is drawn only if its data is there. Columns are read by name: a CSV
may carry more columns (one per NDF parameter beside ndf, say) than the ones read here.
"""
import math
import os
import sys
from collections import defaultdict

# plot_common first: it says what is missing when matplotlib is (and selects the Agg backend).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_common import num, rows, save, use_style  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import PowerNorm  # noqa: E402
import numpy as np  # noqa: E402

# Hammon 2017's layout (slides "Direct only" ... "Approximate diffuse only"): rows the light at 0, 90, 135 degrees
# from the viewer, each row three spheres at albedo 0.75, 0.5, 0.25; columns alpha.
LIGHTS = (0.0, 90.0, 135.0)
ALBEDOS = (0.75, 0.5, 0.25)
SIM_SOURCES = ("simulation, diffuse only", "simulation with spec")
LAMBERT_SOURCES = ("lambert facets: direct only", "lambert facets: direct plus indirect",
                   "lambert facets: indirect only")
BACKGROUND = (0.16, 0.17, 0.22)  # unlit parts of a sphere are black: the background is not
GAP_SPHERE, GAP_CELL = 2, 10     # pixels between the three spheres of a cell, and between cells


def tone(v):
    """The same tone map for every source: pi times the radiance (a white Lambertian facing the light is 1), clipped
    at 1, gamma 2.2."""
    return np.clip(v * math.pi, 0.0, 1.0) ** (1.0 / 2.2)


def alpha_label(a):
    """Hammon's column labels: alpha = 0, 0.25^2, 0.5^2, 0.75^2, 1 (0 is traced at a small alpha: say which)."""
    if a <= 0.001 + 1e-12:
        return f"α = 0\n(drawn at {a:g})"
    r = math.sqrt(a)
    if abs(r * 4 - round(r * 4)) < 1e-9 and r < 1:
        return f"α = {r:g}²\n({a:g})"
    return f"α = {a:g}"


def composite(values, alphas, P):
    """One source's picture: 3 light rows x len(alphas) columns, each cell three spheres (albedo 0.75, 0.5, 0.25)
    side by side. values[(alpha, light, albedo)] is a P x P array (NaN outside the sphere, 0 where unlit)."""
    cell_w = 3 * P + 2 * GAP_SPHERE
    W = len(alphas) * cell_w + (len(alphas) - 1) * GAP_CELL
    H = len(LIGHTS) * P + (len(LIGHTS) - 1) * GAP_CELL
    img = np.empty((H, W, 3))
    img[:, :] = BACKGROUND
    for c, a in enumerate(alphas):
        for r, light in enumerate(LIGHTS):
            for k, albedo in enumerate(ALBEDOS):
                v = values.get((a, light, albedo))
                if v is None:
                    continue
                x0, y0 = c * (cell_w + GAP_CELL) + k * (P + GAP_SPHERE), r * (P + GAP_CELL)
                block = img[y0:y0 + P, x0:x0 + P]
                inside = ~np.isnan(v)
                t = tone(np.nan_to_num(v))
                for ch in range(3):
                    block[:, :, ch] = np.where(inside, t, block[:, :, ch])
    ticks_x = [c * (cell_w + GAP_CELL) + cell_w / 2 for c in range(len(alphas))]
    ticks_y = [r * (P + GAP_CELL) + P / 2 for r in range(len(LIGHTS))]
    return img, ticks_x, ticks_y


def sphere_mask(P):
    """NaN outside the disc of P pixels (fit_pictures.cpp: pixel centers at (2i + 1 - P)/P, (P - 1 - 2j)/P)."""
    c = (2 * np.arange(P) + 1 - P) / P
    x, y = np.meshgrid(c, -c)
    return np.where(x * x + y * y < 1.0, 0.0, np.nan)


def sphere_values(table, P):
    """{source: {(alpha, light, albedo): P x P array}} from spheres.csv's rows of one NDF."""
    mask = sphere_mask(P)
    out = defaultdict(dict)
    for r in table:
        key = (num(r["alpha"]), num(r["light_deg"]), num(r["albedo"]))
        src = out[r["source"]]
        if key not in src:
            src[key] = mask.copy()
        src[key][int(r["py"]), int(r["px"])] = num(r["value"])
    return out


def draw_sources(path, title, sources, values, P, ncols):
    alphas = sorted({k[0] for s in sources for k in values[s]})
    nrows = (len(sources) + ncols - 1) // ncols
    img0, _, _ = composite(values[sources[0]], alphas, P)
    h, w = img0.shape[:2]
    # Inches: a picture's width, the room left of each (light labels), under each (alpha labels, the next title),
    # above all (the two-line title); the figure is sized so that the pictures fill it.
    pic_w, left, gap, top = 6.0, 1.05, 1.0, 0.95
    pic_h = pic_w * h / w
    fig_w, fig_h = ncols * (pic_w + left) + 0.1, nrows * pic_h + (nrows - 1) * gap + top + 0.6
    fig, axes = plt.subplots(nrows, ncols, figsize=(fig_w, fig_h), squeeze=False)
    fig.subplots_adjust(left=left / fig_w, right=1 - 0.1 / fig_w, top=1 - top / fig_h, bottom=0.6 / fig_h,
                        wspace=left / pic_w, hspace=gap / pic_h)
    for ax in axes.flat[len(sources):]:
        ax.axis("off")
    for ax, s in zip(axes.flat, sources):
        img, tx, ty = composite(values[s], alphas, P)
        ax.imshow(img, interpolation="nearest")
        ax.set_xticks(tx)
        ax.set_xticklabels([alpha_label(a) for a in alphas], fontsize=8.5)
        ax.set_yticks(ty)
        ax.set_yticklabels([f"light {lt:g}°" for lt in LIGHTS], fontsize=9)
        ax.tick_params(length=0)
        for sp in ax.spines.values():
            sp.set_visible(False)
        ax.set_title(s, fontsize=10.5, loc="left")
    fig.suptitle(title, fontsize=11)
    save(fig, path, dpi=120)


def spheres(d, ndf, stem, P, table):
    values = sphere_values(table, P)
    models = [s for s in values if s not in SIM_SOURCES and s not in LAMBERT_SOURCES]
    main = [s for s in SIM_SOURCES if s in values] + models
    expl = ("each cell: albedo 0.75, 0.5, 0.25; shown: π·radiance, clipped at 1, gamma 2.2, alike for every source")
    if main:
        draw_sources(os.path.join(d, f"spheres_{stem}.png"),
                     f"{ndf}: lit spheres after Hammon 2017, simulation and models\n({expl})", main, values, P, 2)
    lam = [s for s in LAMBERT_SOURCES if s in values]
    if LAMBERT_SOURCES[2] in values:  # the indirect light is dim at the common exposure: once more, 4x brighter
        bright = LAMBERT_SOURCES[2] + " (4x exposure)"
        values[bright] = {k: 4.0 * v for k, v in values[LAMBERT_SOURCES[2]].items()}
        lam.append(bright)
    if lam:
        draw_sources(os.path.join(d, f"lambert_spheres_{stem}.png"),
                     f"{ndf} with Lambertian facets (ρ_m = 1/π × albedo), traced: single scattering is k = 1\n({expl})",
                     lam, values, P, 2)


SLICE_COLUMNS = 5  # sources per row of slices_STEM.png
SLICE_ALBEDO = 0.75  # fit_pictures.cpp's slice_albedo


def slice_grids(table):
    """(alphas, sources, {(alpha, source): theta_d x theta_h array of pi f / albedo}) from slices.csv's rows of one
    NDF; the simulation first among the sources."""
    by = defaultdict(dict)  # (alpha, source) -> {(theta_h, theta_d): f}
    for r in table:
        by[(num(r["alpha"]), r["source"])][(num(r["theta_h"]), num(r["theta_d"]))] = num(r["value"])
    alphas = sorted({k[0] for k in by})
    sources = list(dict.fromkeys(k[1] for k in by))
    sim = SIM_SOURCES[0]
    sources = [sim] + [s for s in sources if s != sim]
    th = sorted({k[0] for v in by.values() for k in v})
    td = sorted({k[1] for v in by.values() for k in v})
    grids = {k: np.array([[v.get((h, dd), np.nan) for h in th] for dd in td]) * math.pi / SLICE_ALBEDO
             for k, v in by.items()}
    return alphas, sources, grids


def slice_pair(ax, axd, grid, ref, norm, is_ref):
    """One source at one alpha: its slice (ax) and, below, its relative difference to the simulation (axd)."""
    ext = (0, 90, 90, 0)
    im = ax.imshow(grid, extent=ext, cmap="magma", norm=norm, interpolation="nearest")
    if ref is None or is_ref:
        axd.axis("off")
        if is_ref:
            axd.text(0.5, 0.5, "the reference\nof the differences", ha="center", va="center", fontsize=9,
                     transform=axd.transAxes)
        return im, None
    rel = grid / ref - 1.0
    imd = axd.imshow(rel, extent=ext, cmap="RdBu_r", vmin=-0.5, vmax=0.5, interpolation="nearest")
    axd.set_title(f"median |rel. diff| {np.nanmedian(np.abs(rel)):.3f}", fontsize=8.5)
    return im, imd


def slice_colorbar(fig, axes_row, mappable, label, extend):
    """A colorbar right of one row of panels, as tall as the row."""
    top = axes_row[0].get_position()
    cax = fig.add_axes((0.915, top.y0, 0.012, top.height))
    fig.colorbar(mappable, cax=cax, extend=extend).set_label(label, fontsize=8.5)
    cax.tick_params(labelsize=8)


def slices(d, ndf, stem, table):
    """Burley's slices: per alpha, rows of up to SLICE_COLUMNS sources, each slice above its relative difference to
    the simulation; one colour scale per alpha (the simulation's 99th percentile, display gamma 2.2)."""
    alphas, sources, grids = slice_grids(table)
    ncol = min(SLICE_COLUMNS, len(sources))
    chunks = [sources[i:i + ncol] for i in range(0, len(sources), ncol)]
    nrows = 2 * len(alphas) * len(chunks)
    fig, axes = plt.subplots(nrows, ncol, figsize=(1.85 * ncol + 1.6, 2.05 * nrows + 0.9), squeeze=False)
    fig.subplots_adjust(top=1 - 1.0 / fig.get_figheight(), bottom=0.55 / fig.get_figheight(), left=0.1,
                        right=0.9, wspace=0.12, hspace=0.42)
    sim = SIM_SOURCES[0]
    for ia, a in enumerate(alphas):
        ref = grids.get((a, sim))
        vmax = np.nanpercentile(ref, 99) if ref is not None else max(np.nanmax(g) for k, g in grids.items()
                                                                       if k[0] == a)
        norm = PowerNorm(1 / 2.2, vmin=0.0, vmax=vmax)  # display gamma: the dim grazing rows stay readable
        for ic, chunk in enumerate(chunks):
            row = 2 * (ia * len(chunks) + ic)
            imd = None
            for j in range(ncol):
                ax, axd = axes[row, j], axes[row + 1, j]
                if j >= len(chunk) or (a, chunk[j]) not in grids:
                    ax.axis("off")
                    axd.axis("off")
                    continue
                s = chunk[j]
                im, diff = slice_pair(ax, axd, grids[(a, s)], ref, norm, s == sim)
                imd = diff or imd
                ax.set_title(s.replace("simulation, ", "simulation,\n") if s == sim else s, fontsize=9)
                for x in (ax, axd):
                    x.set_xticks([0, 45, 90])
                    x.set_yticks([0, 45, 90])
                    x.tick_params(labelsize=8)
                    if j > 0:
                        x.set_yticklabels([])
                ax.set_xticklabels([])
                if j == 0:
                    ax.set_ylabel(f"α = {a:g}\nθ_d (deg)", fontsize=9)
                    axd.set_ylabel("θ_d (deg)", fontsize=9)
            slice_colorbar(fig, axes[row], im, "π f / albedo", "max")
            if imd is not None:
                slice_colorbar(fig, axes[row + 1], imd, "model / simulation − 1", "both")
    fig.supxlabel("θ_h (deg) across every panel, θ_d (deg) down", fontsize=9.5, y=0.1 / fig.get_figheight())
    fig.suptitle(f"{ndf}: BRDF slices after Burley 2012 (θ_h across, θ_d down, φ_d = 90°), albedo "
                 f"{SLICE_ALBEDO:g}\nsimulation: the diffuse part (k ≥ 1); below each model: its relative difference",
                 fontsize=10.5)
    save(fig, os.path.join(d, f"slices_{stem}.png"), dpi=110)


def missing(d, ndf, stem, table):
    albedos = sorted({num(r["albedo"]) for r in table}, reverse=True)
    alphas = sorted({num(r["alpha"]) for r in table})
    fig, axes = plt.subplots(1, len(albedos), figsize=(5.2 * len(albedos), 4.2), squeeze=False, sharey=True)
    cmap = plt.get_cmap("viridis")
    for ax, alb in zip(axes[0], albedos):
        for i, a in enumerate(alphas):
            pts = sorted((num(r["theta"]), num(r["missing"]), num(r["stderr"])) for r in table
                         if num(r["albedo"]) == alb and num(r["alpha"]) == a)
            t, m, e = zip(*pts)
            ax.errorbar(t, m, yerr=e, marker="o", ms=4, capsize=2, color=cmap(i / max(1, len(alphas) - 1)),
                        label=alpha_label(a).replace("\n", " "))
        ax.axhline(0.5, color="tab:red", ls="--", lw=1)
        ax.text(1, 0.505, "Hammon 2017: \"up to half the light was missing\"", color="tab:red", fontsize=8.5,
                va="bottom")
        ax.set_xlabel("θ_i (deg)")
        ax.set_title(f"albedo {alb:g}", fontsize=10)
        ax.set_ylim(-0.01, 0.6)  # a line at 0 (alpha 0) stays above the axis
        ax.grid(True, alpha=0.3)
    axes[0][0].set_ylabel("1 - E₁/E: the share of the directional albedo\nthat single scattering misses")
    axes[0][-1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.suptitle(f"{ndf}, Lambertian facets, traced: light single scattering misses (sample estimator)", fontsize=10)
    fig.tight_layout()
    save(fig, os.path.join(d, f"missing_{stem}.png"), dpi=120)


def swept_column(stem, header):
    """(family, parameter column) of constants_vs_FAMILY_PARAMETER: the column that the stem ends with."""
    named = [c for c in header if c not in ("ndf", "model", "parameter", "value", "stderr") and
             stem.endswith("_" + c)]
    if not named:
        raise SystemExit(f"fit_plots: {stem}.csv has no column named after its swept parameter")
    x = max(named, key=len)
    return stem[len("constants_vs_"):-len(x) - 1], x


def constants_vs_parameter(d, stem):
    table = rows(os.path.join(d, stem + ".csv"))
    if not table:
        return
    family, x = swept_column(stem, list(table[0].keys()))
    keys = []
    for r in table:
        if (r["model"], r["parameter"]) not in keys:
            keys.append((r["model"], r["parameter"]))
    cols = min(4, len(keys))
    nrows = (len(keys) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(2.9 * cols + 0.4, 2.5 * nrows + 0.7), squeeze=False)
    for ax in axes.flat[len(keys):]:
        ax.axis("off")
    for ax, (model, param) in zip(axes.flat, keys):
        pts = sorted((num(r[x]), num(r["value"]), num(r["stderr"]))
                     for r in table if r["model"] == model and r["parameter"] == param)
        if pts:
            g, v, e = zip(*pts)
            ax.errorbar(g, v, yerr=e, marker="o", ms=4, capsize=3)
        ax.set_title(f"{model}: {param}", fontsize=9.5)
        ax.set_xlabel(f"{family}'s {x}")
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"Fitted constants against {family}'s {x}\n(error bars: one standard error, from the fit's covariance)")
    fig.tight_layout()
    save(fig, os.path.join(d, stem + ".png"), dpi=120)


def main():
    d = sys.argv[1]
    use_style()
    ndfs = rows(os.path.join(d, "ndfs.csv"))
    groups = {}
    for name in ("spheres", "slices", "missing"):
        path = os.path.join(d, name + ".csv")
        groups[name] = defaultdict(list)
        if os.path.exists(path):
            for r in rows(path):
                groups[name][r["ndf"]].append(r)
    for n in ndfs:
        ndf, stem = n["ndf"], n["stem"]
        if groups["spheres"][ndf]:
            spheres(d, ndf, stem, int(n["pixels"]), groups["spheres"][ndf])
        if groups["slices"][ndf]:
            slices(d, ndf, stem, groups["slices"][ndf])
        if groups["missing"][ndf]:
            missing(d, ndf, stem, groups["missing"][ndf])
    for name in sorted(os.listdir(d)):
        if name.startswith("constants_vs_") and name.endswith(".csv"):
            constants_vs_parameter(d, name[:-len(".csv")])


if __name__ == "__main__":
    main()
