#!/usr/bin/env python3
"""Learns the per-level scales of δ_x's intervals and checks them (docs/analysis.md, "Calibration").

Usage: interval_scales.py LEARN.csv [LEARN.csv ...] [--check CHECK.csv ...]

The files are the per-curve output of bench/analysis_calibration. For every accepted curve and each
level L (68 %, 95 %) the score is how far the interval's half-width on the side of the truth must be
stretched about the estimate to reach the truth. The scale of level L is the split-conformal
quantile of the learning curves' scores: the ceil((n + 1) L)-th smallest of n. The check files are
then scored with those scales and never used to choose them.
Standard library only, so it runs wherever the bench does.
"""
import csv
import math
import sys
from collections import OrderedDict

LEVELS = (("68", 0.6826894921370859), ("95", 0.95))


def score(row, level):
    truth, estimate = float(row["delta_x_true"]), float(row["delta_x"])
    low, high = float(row[f"ci{level}_low"]), float(row[f"ci{level}_high"])
    reach = high - estimate if truth >= estimate else estimate - low
    gap = abs(truth - estimate)
    if gap == 0.0:
        return 0.0
    return gap / reach if reach > 0.0 else math.inf


def read(paths):
    rows = []
    for path in paths:
        with open(path, newline="", encoding="utf-8") as f:
            rows += list(csv.DictReader(f))
    return rows


def conformal_scale(scores, level):
    ordered = sorted(scores)
    rank = min(len(ordered), math.ceil((len(ordered) + 1) * level))
    return ordered[rank - 1]


def table(title, rows, scales):
    groups = OrderedDict()
    for row in rows:
        groups.setdefault(row["group"], []).append(row)
    print(f"\n{title}\n")
    print("| group | curves | accepted | δ_x 68 % (scaled) | δ_x 95 % (scaled) | δ_x 68 % (unscaled) | "
          "δ_x 95 % (unscaled) |")
    print("|---|---|---|---|---|---|---|")
    for name, members in list(groups.items()) + [("all", rows)]:
        accepted = [r for r in members if r["accepted"] == "1"]
        n = max(1, len(accepted))
        covered = {lvl: sum(score(r, lvl) <= scales[lvl] for r in accepted) for lvl, _ in LEVELS}
        raw = {lvl: sum(score(r, lvl) <= 1.0 for r in accepted) for lvl, _ in LEVELS}
        print(f"| {name} | {len(members)} | {len(accepted)} | {100 * covered['68'] / n:.1f} % | "
              f"{100 * covered['95'] / n:.1f} % | {100 * raw['68'] / n:.1f} % | {100 * raw['95'] / n:.1f} % |")


def main(argv):
    if "--check" in argv:
        cut = argv.index("--check")
        learn, check = argv[:cut], argv[cut + 1:]
    else:
        learn, check = argv, []
    if not learn:
        sys.exit("interval_scales.py: name at least one per-curve file to learn from")
    learning = read(learn)
    accepted = [r for r in learning if r["accepted"] == "1"]
    scales = {lvl: conformal_scale([score(r, lvl) for r in accepted], p) for lvl, p in LEVELS}
    print(f"learned on {', '.join(learn)} ({len(accepted)} accepted curves): "
          f"scale 68 % = {scales['68']:.4f}, scale 95 % = {scales['95']:.4f}")
    table("Learning set", learning, scales)
    for path in check:
        table(f"Check: {path}", read([path]), scales)


if __name__ == "__main__":
    main(sys.argv[1:])
