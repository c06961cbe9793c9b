#!/usr/bin/env python3
"""How often the bootstrap's noise model reads no walk in F, and what that does to x_c's own interval
(docs/analysis.md, "The walk read on rows that are means, checked on held-out 38").

Usage: walk_read_zero.py CALIBRATION.csv [CALIBRATION.csv ...] [--quantity x_c|x_p]

The files are the per-curve output of bench/analysis_calibration (its `force_walk_share` column is F's
walk per row over F_c as the noise model read it). For each group of accepted curves the table gives
how many had F's walk read as zero and how often the quantity's own 68 % interval (the bootstrap's sd,
before any factor: the files are run with calibrated intervals off) held the truth, for those curves
and for the rest. A walk read as zero leaves the interval to the white term alone.
"""
import argparse

import pandas as pd


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+")
    parser.add_argument("--quantity", default="x_c", choices=["x_c", "x_p"])
    args = parser.parse_args()
    q = args.quantity
    curves = pd.concat([pd.read_csv(f) for f in args.files])
    curves = curves[(curves.accepted == 1) & curves[f"{q}_sd"].notna() & (curves[f"{q}_sd"] > 0)]

    def covered(part):
        if part.empty:
            return "-"
        inside = ((part[q] - part[f"{q}_true"]).abs() < part[f"{q}_sd"]).mean()
        return f"{100 * inside:.0f} %"

    print(f"| group | accepted | F's walk read zero | {q}'s own 68 % covers: all | walk zero | walk read |")
    print("|---|---|---|---|---|---|")
    for group, part in curves.groupby("group", sort=True):
        zero = part.force_walk_share == 0
        print(f"| {group} | {len(part)} | {zero.sum()} ({100 * zero.mean():.0f} %) | {covered(part)} | "
              f"{covered(part[zero])} | {covered(part[~zero])} |")


if __name__ == "__main__":
    main()
