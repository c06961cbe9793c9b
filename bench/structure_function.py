#!/usr/bin/env python3
"""What kind of noise a loading curve carries, by its structure function (docs/analysis.md, "What a DEM
curve's noise is").

Usage: structure_function.py CURVES.csv [CURVES.csv ...] [--force NAME] [--energy NAME]

For F and E_e of each file (columns named NAME[unit]; default force_top and elastic_energy, as
`rupture run` writes them) it prints S(L)/S(1) at lags L = 1, 2, 3, 4, 6, 8, 12, 16, where S(L) is
the mean square of the second differences y[i+L] - 2 y[i] + y[i-L] over the loading phase: the rows
from 10 % to 95 % of the way to the force maximum, leaving out values more than 10 robust sd from
their median (a break's drop is no noise). The analysis's noise model (src/analysis/bootstrap.hpp)
fits the same S(L) with white noise (the same at every lag), a random walk (growing as L) and the
curve's own curvature (as L^4). A ringing of period P rows is none of these: its S(L) falls to
near 0 at L = P and its multiples. The shortest lag where S(L) dips below half of S(1), if any, is
printed as the ringing's period in rows. Standard library only.
"""
import sys

from curve_table import read_columns

LAGS = (1, 2, 3, 4, 6, 8, 12, 16)


def structure_function(y, low, high, lag):
    """Mean square of the lag-L second differences over y[low:high], outliers left out (None if no
    value is left)."""
    d = [y[i + lag] - 2.0 * y[i] + y[i - lag] for i in range(low + lag, high - lag)]
    if not d:
        return None
    median = sorted(d)[len(d) // 2]
    spread = 1.4826 * sorted(abs(v - median) for v in d)[len(d) // 2]
    kept = [v for v in d if spread == 0.0 or abs(v - median) <= 10.0 * spread]
    return sum(v * v for v in kept) / len(kept)


def ratios(y, low, high):
    """S(L)/S(1) for each lag in LAGS (None where undefined)."""
    first = structure_function(y, low, high, 1)
    out = []
    for lag in LAGS:
        s = structure_function(y, low, high, lag)
        out.append(s / first if s is not None and first else None)
    return out


def ringing_period(r):
    """The shortest lag where S(L)/S(1) dips below 0.5 (the period; its multiples dip too), or None."""
    dips = [lag for lag, v in zip(LAGS, r) if lag > 1 and v is not None and v < 0.5]
    return dips[0] if dips else None


def main(argv):
    names = {"--force": "force_top", "--energy": "elastic_energy"}
    paths = []
    args = iter(argv)
    for a in args:
        if a in names:
            names[a] = next(args, None) or sys.exit(f"{a} needs a column name")
        else:
            paths.append(a)
    if not paths:
        sys.exit(__doc__)
    print("| curve | rows | curve's column | " + " | ".join(f"L={lag}" for lag in LAGS) + " | ringing period [rows] |")
    print("|---|---|---|" + "---|" * len(LAGS) + "---|")
    for path in paths:
        force, energy = zip(*read_columns(path, (names["--force"], names["--energy"]), "a curves.csv file",
                                          "choose one with --force / --energy"))
        top = max(range(len(force)), key=lambda i: force[i])
        low, high = int(0.1 * top), int(0.95 * top)
        for label, y in (("F", force), ("E_e", energy)):
            r = ratios(y, low, high)
            cells = " | ".join("-" if v is None else f"{v:.3g}" for v in r)
            period = ringing_period(r)
            print(f"| {path} | {high - low} | {label} | {cells} | {'-' if period is None else period} |")


if __name__ == "__main__":
    main(sys.argv[1:])
