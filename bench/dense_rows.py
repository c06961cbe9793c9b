"""What the dense-run bench scripts share: reading a curves.csv of `rupture run` (comment lines skipped,
columns found by their name's start, one-line errors naming the file and the fix) and the means of
its rows over a sliding window, each window summed on its own. Standard library only."""
import csv
import sys


def read_columns(path, prefixes):
    """The columns whose names start with `prefixes` (e.g. "strain[") as rows of floats."""
    try:
        f = open(path, encoding="utf-8")
    except OSError as e:
        sys.exit(f"{path}: cannot read it ({e.strerror}); name a curves.csv of rupture run")
    with f:
        reader = csv.reader(line for line in f if not line.startswith("#"))
        header = next(reader, [])
        columns = [next((i for i, name in enumerate(header) if name.startswith(p)), None) for p in prefixes]
        if None in columns:
            names = ", ".join(p.rstrip("[") for p in prefixes)
            sys.exit(f"{path}: no {names} column; name a curves.csv of rupture run")
        return [[float(r[i]) for i in columns] for r in reader]


def window_means(rows, width):
    """Per window of `width` consecutive rows (first rows[0:width], then one row on), each column's mean."""
    return [[sum(r[k] for r in rows[i:i + width]) / width for k in range(len(rows[0]))]
            for i in range(len(rows) - width + 1)]


def force_top(means, low=0.3, high=0.5):
    """The index of the window whose mean top force (column 1) is largest where its mean strain
    (column 0) lies in (low, high) %, or None: a DEM tissue's force peak, away from the ramp's start
    and the fragments."""
    inside = [i for i, m in enumerate(means) if low < m[0] < high]
    return max(inside, key=lambda i: means[i][1]) if inside else None
