#!/usr/bin/env python3
"""Learns the per-level scales of δ_x's intervals and checks them (docs/analysis.md, "Calibration").

Usage: interval_scales.py LEARN.csv [LEARN.csv ...] [--use KIND=S68,S95 ...] [--skip-shape NAME ...]
                          [--check CHECK.csv ...]

The files are the per-curve output of bench/analysis_calibration. For every accepted curve and each
level L (68 %, 95 %) the score is how far the interval's half-width on the side of the truth must be
stretched about the estimate to reach the truth. The scale of level L is the split-conformal
quantile of the learning curves' scores, the ceil((n + 1) L)-th smallest of n, taken separately for
each kind of noise the analysis tells apart (the `noise` column: white, random walk), as
src/analysis/analysis.hpp applies them. The check files are then scored with those scales and never
used to choose them. `--use "random walk=1,0.6119"` scores with given factors for one kind instead of
the learned ones (what src/analysis/analysis.hpp applies where a learned factor failed its check).
`--skip-shape "uniform [0.3,0.8]"` leaves that shape's curves out of learning and checking alike (a
case outside the calibration's domain, documented on its own). As in the analysis, the 95 % interval
is never inside the 68 % one: a curve counts as covered at
95 % when either scaled interval reaches the truth.
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


COLUMNS = ("group", "noise", "accepted", "delta_x_true", "delta_x", "ci68_low", "ci68_high", "ci95_low",
           "ci95_high")


def read(paths, skipped=()):
    rows = []
    for path in paths:
        try:
            with open(path, newline="", encoding="utf-8") as f:
                table = csv.DictReader(f)
                missing = [c for c in COLUMNS if c not in (table.fieldnames or [])]
                if missing:
                    sys.exit(f"{path}: no column {', '.join(missing)}; give the per-curve file that "
                             "bench/analysis_calibration writes as its third argument")
                rows += [dict(r, source=path) for r in table if r.get("shape") not in skipped]
        except OSError as e:
            sys.exit(f"{path}: cannot read it ({e.strerror}); name an existing per-curve file")
    return rows


def parse_use(text):
    """KIND=S68,S95 as (kind, {level: factor})."""
    kind, _, factors = text.partition("=")
    try:
        s68, s95 = (float(f) for f in factors.split(","))
    except ValueError:
        sys.exit(f"interval_scales.py: --use '{text}': give KIND=S68,S95, e.g. --use \"random walk=1,0.6119\"")
    return kind, {"68": s68, "95": s95}


def conformal_scale(scores, level):
    ordered = sorted(scores)
    rank = min(len(ordered), math.ceil((len(ordered) + 1) * level))
    return ordered[rank - 1]


def learn_scales(rows):
    """{noise kind: {level: scale}} from the accepted rows of each kind."""
    scales = {}
    for kind in sorted({r["noise"] for r in rows}):
        accepted = [r for r in rows if r["noise"] == kind and r["accepted"] == "1"]
        if accepted:
            scales[kind] = {lvl: conformal_scale([score(r, lvl) for r in accepted], p) for lvl, p in LEVELS}
    return scales


def is_covered(row, level, by_level):
    """Whether the scaled interval of `level` reaches the truth (the 95 % one holds the 68 % one)."""
    reached = score(row, level) <= by_level[level]
    return reached or (level == "95" and score(row, "68") <= by_level["68"])


def table(title, rows, scales):
    groups = OrderedDict()
    for row in rows:
        groups.setdefault(row["group"], []).append(row)
    print(f"\n{title}\n")
    print("| group | curves | read as random walk | accepted | δ_x 68 % (scaled) | δ_x 95 % (scaled) | "
          "δ_x 68 % (unscaled) | δ_x 95 % (unscaled) |")
    print("|---|---|---|---|---|---|---|---|")
    for name, members in list(groups.items()) + [("all", rows)]:
        accepted = [r for r in members if r["accepted"] == "1"]
        n = max(1, len(accepted))
        for r in accepted:
            if r["noise"] not in scales:
                sys.exit(f"{r['source']}: no scale for {r['noise']} noise; learn on curves of that kind "
                         "or give it with --use")
        covered = {lvl: sum(is_covered(r, lvl, scales[r["noise"]]) for r in accepted) for lvl, _ in LEVELS}
        raw = {lvl: sum(score(r, lvl) <= 1.0 for r in accepted) for lvl, _ in LEVELS}
        walks = sum(r["noise"] == "random walk" for r in members)
        print(f"| {name} | {len(members)} | {walks} | {len(accepted)} | {100 * covered['68'] / n:.1f} % | "
              f"{100 * covered['95'] / n:.1f} % | {100 * raw['68'] / n:.1f} % | {100 * raw['95'] / n:.1f} % |")


def main(argv):
    if "--check" in argv:
        cut = argv.index("--check")
        argv, check = argv[:cut], argv[cut + 1:]
    else:
        check = []
    learn, given, skipped = [], {}, set()
    args = iter(argv)
    for arg in args:
        if arg == "--use":
            kind, by_level = parse_use(next(args, ""))
            given[kind] = by_level
        elif arg == "--skip-shape":
            name = next(args, "")
            if not name:
                sys.exit("interval_scales.py: --skip-shape needs a shape name as the files write it, "
                         "e.g. --skip-shape \"uniform [0.3,0.8]\"")
            skipped.add(name)
        else:
            learn.append(arg)
    if not learn:
        sys.exit("interval_scales.py: name at least one per-curve file to learn from")
    learning = read(learn, skipped)
    present = {r.get("shape") for r in read(learn + check)}
    for name in sorted(skipped - present):
        sys.exit(f"interval_scales.py: --skip-shape '{name}': no curve of that shape in the files; "
                 "give the name as their `shape` column writes it")
    scales = learn_scales(learning)
    print(f"learned on {', '.join(learn)}:")
    for kind, by_level in scales.items():
        n = sum(r["noise"] == kind and r["accepted"] == "1" for r in learning)
        print(f"  {kind} noise ({n} accepted curves): scale 68 % = {by_level['68']:.4f}, "
              f"scale 95 % = {by_level['95']:.4f}")
    for kind, by_level in given.items():
        print(f"  scored with {kind} noise: scale 68 % = {by_level['68']:.4f}, scale 95 % = {by_level['95']:.4f}")
        scales[kind] = by_level
    table("Learning set", learning, scales)
    for path in check:
        table(f"Check: {path}", read([path], skipped), scales)


if __name__ == "__main__":
    main(sys.argv[1:])
