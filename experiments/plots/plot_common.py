"""What smithlab's plot scripts (report_plots.py, fit_plots.py) share: reading the CSV files their runs wrote, one
style for every figure, saving a figure the same way byte for byte, and placing point labels that do not overlap."""
import csv
import math
import sys

try:
    import matplotlib
except ImportError:
    # The exit status smithlab reads as "no matplotlib" (output/plot_script.hpp): figures left out, the run goes on.
    print("the figures need matplotlib: apt-get install python3-matplotlib", file=sys.stderr)
    sys.exit(4)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Font sizes in points at the figure's own size: the figures are drawn 7 to 12 inches wide, to be shown at about
# that width (a page, a screen), where 9 pt stays readable.
STYLE = {
    "font.size": 10,
    "axes.titlesize": 10,
    "axes.labelsize": 10,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "legend.fontsize": 9,
    "figure.titlesize": 11,
    "legend.framealpha": 0.9,
    "savefig.facecolor": "white",
}


def use_style():
    """The rcParams of every figure (call once, before drawing)."""
    plt.rcParams.update(STYLE)


def save(fig, path, dpi=130):
    """Writes fig as PNG with fixed metadata (no software version, no date): the same CSVs give the same bytes."""
    fig.savefig(path, dpi=dpi, metadata={"Software": None})
    plt.close(fig)


def rows(path):
    """The rows of a CSV file with a header, as dicts."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(s):
    """A field as a number; an empty one is NaN."""
    return float(s) if s not in ("", None) else math.nan


def place_labels(ax, xy, texts, fontsize=8, colors=None):
    """Writes texts[i] beside the point xy[i] (data coordinates), each at the first of a ring of offsets, growing
    outwards, where its box overlaps neither a label placed before nor any point's marker; a label moved away from
    its point gets a thin leader line. Greedy and deterministic (the points in the given order)."""
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    px = [tuple(ax.transData.transform(p)) for p in xy]
    r_mark = 4.0 * fig.dpi / 72.0  # a marker's half width, in pixels
    blocked = [(x - r_mark, y - r_mark, x + r_mark, y + r_mark) for x, y in px]
    frame = ax.get_window_extent(renderer)
    scale = fig.dpi / 72.0
    directions = [(1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)]
    for i, ((x, y), text) in enumerate(zip(px, texts)):
        t = fig.text(0, 0, text, fontsize=fontsize)  # figure coordinates: measured the same on any axis scale
        bb = t.get_window_extent(renderer)
        pad = 2.0 * scale  # the free margin kept around a label
        w, h = bb.width + 2 * pad, bb.height + 2 * pad
        t.remove()
        chosen = None
        for radius in (3, 7, 12, 18, 26, 36, 48):
            for dx, dy in directions:
                ox, oy = dx * radius * scale, dy * radius * scale
                x0 = x + ox if dx >= 0 else x + ox - w
                y0 = y + oy if dy >= 0 else y + oy - h
                if dx == 0:
                    x0 = x - w / 2
                if dy == 0:
                    y0 = y - h / 2
                box = (x0, y0, x0 + w, y0 + h)
                inside = frame.x0 <= box[0] and box[2] <= frame.x1 and frame.y0 <= box[1] and box[3] <= frame.y1
                if inside and not any(_overlap(box, b) for b in blocked):
                    chosen = (box, radius)
                    break
            if chosen:
                break
        if chosen is None:  # nowhere free: the first offset, overlapping
            chosen = ((x + 3 * scale, y + 3 * scale, x + 3 * scale + w, y + 3 * scale + h), 3)
        box, radius = chosen
        blocked.append(box)
        cx, cy = ax.transData.inverted().transform((box[0] + pad, box[1] + pad))
        ax.annotate(text, xy[i], xytext=(cx, cy), textcoords="data", fontsize=fontsize, ha="left", va="bottom",
                    color=colors[i] if colors else "black",
                    arrowprops=dict(arrowstyle="-", lw=0.5, color="0.5", shrinkA=0, shrinkB=2) if radius > 3 else None)


def _overlap(a, b):
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
