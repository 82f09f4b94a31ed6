#!/usr/bin/python3
"""Draws the furnace of `smithlab fit`'s energy-compensation tables from the CSV files it wrote into DIR:
compensation_plots.py DIR.

Needs Debian's python3-matplotlib (installed by .ci/deps). experiments/compensation/table_files.cpp writes the data:
  furnace_tables.csv   ndf,g2,table,alpha,furnace_error,cos_theta: per alpha of a table's check grid, the worst
                       |compensated albedo - 1| by the tables over theta_i <= 85 degrees
  furnace.csv          ndf,g2,material,part,form,alpha,theta_i,compensated,traced,traced_stderr: against the walk
and this script draws furnace.png: left, the tables' furnace error against alpha (one line per table and G2); right,
compensated - traced at each walk cell with 3 standard errors as bars, one panel row per material and part (a
conductor's forms in one panel, a colour each, its NDFs a marker each; dashed: the separable G2).
"""
import os
import sys
from collections import defaultdict

# plot_common first: it says what is missing when matplotlib is (and selects the Agg backend).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_common import num, rows, save, use_style  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main(out):
    use_style()
    tables = rows(os.path.join(out, "furnace_tables.csv"))
    cells = rows(os.path.join(out, "furnace.csv"))
    parts = {"total": 0, "R": 1, "T": 2}
    markers = {"kulla-conty": "o", "turquin": "s", "fdez-aguera": "^", "walk-orders": "D"}
    ndf_markers = "osD^vP*X"  # a conductor panel's NDFs, one marker each (its colours are the forms)
    materials = sorted({(r["material"], r["part"]) for r in cells},
                       key=lambda m: (m[0] != "mirror", not m[0].startswith("conductor"), m[0], parts[m[1]]))
    n = max(1, len(materials))
    fig = plt.figure(figsize=(12, 2.2 + 1.6 * n))
    grid = fig.add_gridspec(n, 2, width_ratios=(1.1, 1.0))
    ax = fig.add_subplot(grid[:, 0])
    lines = defaultdict(list)
    for r in tables:
        lines[(r["ndf"], r["g2"], r["table"])].append((num(r["alpha"]), max(num(r["furnace_error"]), 1e-7)))
    for (ndf, g2, table), pts in sorted(lines.items()):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], lw=1.2,
                ls="-" if g2 == "height-correlated" else "--", label=f"{ndf} {g2}: {table}")
    ax.axhline(1e-3, color="k", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("alpha")
    ax.set_ylabel("worst |compensated albedo - 1|, theta_i <= 85 deg (floor 1e-7)")
    ax.set_title("The furnace by the tables (check grid)")
    ax.legend(fontsize=7, loc="upper right")
    labelled = set()  # the forms already in a legend (one entry each, whatever the NDF, G2 and alpha)
    for k, (material, part) in enumerate(materials):
        a = fig.add_subplot(grid[k, 1])
        series = defaultdict(list)
        for r in cells:
            if (r["material"], r["part"]) == (material, part):
                series[(r["ndf"], r["g2"], num(r["alpha"]), r["form"])].append(
                    (num(r["theta_i"]), num(r["compensated"]) - num(r["traced"]), 3 * num(r["traced_stderr"])))
        forms = sorted({key[3] for key in series})
        alphas = sorted({key[2] for key in series})
        ndfs = sorted({key[0] for key in series})
        for (ndf, g2, alpha, form), pts in sorted(series.items()):
            pts.sort()
            style = dict(capsize=2, lw=1, ls="-" if g2 == "height-correlated" else "--", ms=3,
                         marker=markers.get(form, "o"))
            if len(forms) > 1:
                # A conductor's forms: one colour each, darker the rougher; the legend names the forms only.
                shade = 0.3 + 0.7 * alphas.index(alpha) / max(1, len(alphas) - 1)
                style.update(color=f"C{forms.index(form)}", alpha=shade,
                             marker=ndf_markers[ndfs.index(ndf) % len(ndf_markers)])
                style["label"] = None if (k, form) in labelled else f"{form} (darker: alpha up to {alphas[-1]:g})"
                labelled.add((k, form))
            else:
                style["label"] = f"{ndf} {g2} alpha {alpha:g}"
            a.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=[p[2] for p in pts], **style)
        a.axhline(0.0, color="k", lw=0.6)
        a.set_title(f"{material}: {part}" if part != "total" else material, fontsize=9)
        a.set_ylabel("compensated - traced", fontsize=8)
        if k == n - 1:
            a.set_xlabel("theta_i (degrees)")
        if len(forms) > 1 and len(ndfs) > 1:
            for i, ndf in enumerate(ndfs):  # the NDFs by marker, beside the forms by colour
                a.plot([], [], ls="none", color="k", marker=ndf_markers[i % len(ndf_markers)], ms=3, label=ndf)
        if k == 0 or len(forms) > 1:
            a.legend(fontsize=6, ncol=2 if len(forms) == 1 or len(ndfs) > 1 else 1, loc="lower left")
    fig.tight_layout()
    save(fig, os.path.join(out, "furnace.png"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: compensation_plots.py DIR")
    main(sys.argv[1])
