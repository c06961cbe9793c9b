#!/usr/bin/env python3
"""x_c of DEM runs against a reference taken from their dense rows (docs/analysis.md, "x_c of a loading cut
by a collapse").

Usage: dem_x_c_reference.py [--top-range LOW,HIGH] [--widths A,B] TABLE.csv DENSE_CURVES...

DENSE_CURVES are curves.csv files written with a row every few steps (`rupture run CONFIG --set
output.interval=10`); TABLE.csv is the table bench/dem_row_means.py appends its analyses of those files to.
Each run's reference x_c is the strain where the running mean of its top force over A and over B dense
rows peaks (default 20 and 40; within LOW-HIGH % strain, default 0.3-0.5 %, the default study's; the mean
of the two), so no filter and no peak fit enter it. Printed: each
run's reference, then per row spacing and kind the accepted analyses' x_c error against it (mean and rms,
in % strain, as rupture run writes it) and the share whose error lies within their reported sd. Standard library only.
"""
import csv
import math
import os
import statistics
import sys

from curve_table import read_columns
from dense_rows import found_force_top, no_other_options, parse_rows, take_option, take_top_range, window_means


def reference_x_c(path, widths, low, high):
    rows = read_columns(path, ("strain", "force_top"))
    peaks = []
    for width in widths:
        means = window_means(rows, width)
        peaks.append(means[found_force_top(means, low, high, path)][0])
    return statistics.mean(peaks)


def main(argv):
    args = argv[1:]
    low, high = take_top_range(args)
    widths = [parse_rows(w, "--widths") for w in take_option(args, "--widths", "20,40").split(",")]
    no_other_options(args, ("--top-range", "--widths"))
    if len(args) < 2:
        sys.exit(__doc__)
    table = args[0]
    references = {os.path.realpath(path): reference_x_c(path, widths, low, high) for path in args[1:]}
    for path, x_c in references.items():
        print(f"{path}: reference x_c {x_c:.4f} %")
    groups = {}
    with open(table, newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f):
            dense = os.path.realpath(row["dense"])
            if dense in references and row["accepted"] == "1":
                error = float(row["x_c"]) - references[dense]
                groups.setdefault((int(row["spacing"]), row["kind"]), []).append((error, float(row["x_c_sd"])))
    if not groups:
        sys.exit(f"{table}: no accepted analysis of the named curves; name the dense files as the table does")
    print("| rows every (steps) | kind | accepted | x_c error mean [%] | rms [%] | within its sd |")
    print("|---|---|---|---|---|---|")
    for (spacing, kind), values in sorted(groups.items()):
        errors = [e for e, _ in values]
        within = sum(abs(e) < sd for e, sd in values) / len(values)
        rms = math.sqrt(sum(e * e for e in errors) / len(errors))
        print(f"| {spacing} | {kind} | {len(values)} | {statistics.mean(errors):+.4f} | {rms:.4f} | {100 * within:.0f} % |")


if __name__ == "__main__":
    main(sys.argv)
