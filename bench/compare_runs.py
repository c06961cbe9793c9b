#!/usr/bin/env python3
"""Scores a change to the analysis by its effect: the same calibration set run before and after it.

Usage: compare_runs.py BEFORE.csv AFTER.csv --use Q:KIND=S68,S95 [--use ...]

BEFORE and AFTER are per-curve files of bench/analysis_calibration on the same set (the same curves
and seeds, row by row). Prints the curves the change rejects or accepts anew, how many rows moved,
and, over the curves both accept, how many intervals cover the truth before and after for each
quantity Q (delta_x, x_c, x_p) and level, each scaled by the factors given for its kind of noise
(`--use "x_c:random walk=1.0468,1.1232"`; a kind without factors is scored at factor 1, as the
analysis does where none is calibrated). The coverage rule is interval_scales.py's.
Standard library only.
"""
import sys

import interval_scales as scales

QUANTITIES = ("delta_x", "x_c", "x_p")
KEY = ("group", "shape", "rows", "seed")
ESTIMATES = ("accepted", "delta_x", "delta_x_sd", "x_c", "x_c_sd", "x_p", "x_p_sd")


def parse_use(text):
    quantity, _, rest = text.partition(":")
    if quantity not in QUANTITIES:
        sys.exit(f"compare_runs.py: --use '{text}': start with delta_x:, x_c: or x_p:")
    kind, factors = scales.parse_use(rest)
    return quantity, kind, factors


def main(argv):
    files, factors = [], {q: {} for q in QUANTITIES}
    args = iter(argv)
    for arg in args:
        if arg == "--use":
            quantity, kind, by_level = parse_use(next(args, ""))
            factors[quantity][kind] = by_level
        else:
            files.append(arg)
    if len(files) != 2:
        sys.exit("usage: compare_runs.py BEFORE.csv AFTER.csv --use Q:KIND=S68,S95 [--use ...]")
    before, after = (scales.read([path]) for path in files)
    if [tuple(r[k] for k in KEY) for r in before] != [tuple(r[k] for k in KEY) for r in after]:
        sys.exit(f"{files[1]}: not the same curves as {files[0]} row by row; run the same set and count")

    lost = [b for b, a in zip(before, after) if b["accepted"] == "1" and a["accepted"] != "1"]
    gained = [a for b, a in zip(before, after) if b["accepted"] != "1" and a["accepted"] == "1"]
    moved = sum(any(b[c] != a[c] for c in ESTIMATES) for b, a in zip(before, after))
    both = [(b, a) for b, a in zip(before, after) if b["accepted"] == "1" and a["accepted"] == "1"]
    print(f"{len(before)} curves: accepted {sum(r['accepted'] == '1' for r in before)} before, "
          f"{sum(r['accepted'] == '1' for r in after)} after; {moved} rows moved")
    for title, rows in (("rejected by the change", lost), ("accepted anew", gained)):
        for r in rows:
            print(f"  {title}: {r['group']}, {r['shape']}, {r['rows']} rows, seed {r['seed']}")

    print(f"\nOver the {len(both)} curves both accept, covered before -> after:\n")
    print("| quantity | 68 % | 95 % |")
    print("|---|---|---|")
    worst = 0
    for quantity in QUANTITIES:
        scales.QUANTITY = quantity
        cells = []
        for level, _ in scales.LEVELS:
            counts = [sum(scales.is_covered(r, level, factors[quantity].get(r["noise"], {"68": 1.0, "95": 1.0}))
                          for r in run) for run in zip(*both)]
            worst = min(worst, counts[1] - counts[0])
            cells.append(f"{counts[0]} -> {counts[1]}")
        print(f"| {quantity} | {cells[0]} | {cells[1]} |")
    print(f"\nlargest fall in covered curves: {-worst}; curves lost: {len(lost)}")


if __name__ == "__main__":
    main(sys.argv[1:])
