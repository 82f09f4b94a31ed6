"""What smithlab's plot scripts (report_plots.py, fit_plots.py) share: reading the CSV files their runs wrote."""
import csv
import math


def rows(path):
    """The rows of a CSV file with a header, as dicts."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(s):
    """A field as a number; an empty one is NaN."""
    return float(s) if s not in ("", None) else math.nan
