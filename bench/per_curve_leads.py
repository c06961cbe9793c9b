#!/usr/bin/env python3
"""The measurements on the stored per-curve files that docs/analysis.md quotes as leads, not as
shipped numbers ("Two leads on x_p's errors", "Intervals below the table's lowest noise").

Usage: per_curve_leads.py [DIR]   (DIR: bench/results/calibration, the default)

1. The replicates' mean: on held-outs 20-25, how x_p's and δ_x's errors correlate with the bootstrap's
   bias b, and their rms relative error when the estimate moves by k b (k = 1.5: the replicates' mean,
   since the files' estimates already hold half of b subtracted).
2. Shape and sampling at low white noise: on the held-out 20-24 and 26 files at 0.06-0.14 % (curves
   scored as white), the 68.27 % quantile of δ_x's scores per law family and row count.
3. White noise read as a walk at low noise: the curves of the white groups of held-outs 20-24's low
   files scored as a walk, their shapes and rows, and δ_x's coverage with the walk's factors of that day.
Curves are scored as in bench/interval_scales.py (a curve quiet below 0.05 % of both peaks counts as
a walk). Needs pandas.
"""
import math
import pathlib
import sys

import numpy as np
import pandas as pd

HELD_OUT = ["held-out-20.csv", "held-out-21.csv", "held-out-22-edge.csv", "held-out-23.csv",
            "held-out-24-edge.csv", "held-out-25.csv"]
LOW = [f"held-out-{n}-low.csv" for n in range(20, 25)]
WALK_FACTORS = (1.0137, 1.1266)  # δ_x's random-walk factors when these leads were measured (held-out 22 to 34)


def accepted(paths):
    frames = []
    for path in paths:
        if not path.exists():
            sys.exit(f"per_curve_leads.py: no {path}; name the folder of the per-curve files")
        frames.append(pd.read_csv(path).assign(file=path.name))
    d = pd.concat(frames)
    d = d[d.accepted == 1].copy()
    quiet = d[["force_white_share", "energy_white_share"]].max(axis=1) < 5e-4
    d["scored"] = np.where(quiet, "random walk", d["noise"])
    return d


def delta_score(row, level):
    """How far the δ_x interval's half-width on the truth's side must stretch to reach the truth."""
    gap = row.delta_x_true - row.delta_x
    reach = row[f"ci{level}_high"] - row.delta_x if gap >= 0 else row.delta_x - row[f"ci{level}_low"]
    return abs(gap) / reach if reach > 0 else math.inf


def replicates_mean(d):
    print("1. The replicates' mean (held-outs 20-25): correlation of the error with b, rms relative error "
          "at estimate + k b")
    for quantity in ("x_p", "delta_x"):
        for kind in ("random walk", "white"):
            w = d[d.scored == kind]
            error, bias, truth = w[quantity] - w[f"{quantity}_true"], w[f"{quantity}_bias"], w[f"{quantity}_true"]
            rms = [100 * np.sqrt((((error + k * bias) / truth) ** 2).mean()) for k in (0.0, 1.0, 1.5, 2.0)]
            print(f"   {quantity:8s} {kind:12s} {len(w):5d} curves: corr {np.corrcoef(error, bias)[0, 1]:+.2f}, "
                  f"slope {np.polyfit(bias, error, 1)[0]:+.2f}; "
                  "rms at k = 0, 1, 1.5, 2: " + ", ".join(f"{r:.2f} %" for r in rms))
    print("   δ_x per group, relative error as shipped -> at the replicates' mean (k = 1.5): rms, median |e|")
    for (kind, group), w in d.groupby(["scored", "group"]):
        if len(w) < 20:
            continue
        now = (w.delta_x - w.delta_x_true) / w.delta_x_true
        mean = now + 1.5 * w.delta_x_bias / w.delta_x_true
        print(f"   {kind:12s} {group:14s} {len(w):4d}: rms {100 * np.sqrt((now ** 2).mean()):.2f} -> "
              f"{100 * np.sqrt((mean ** 2).mean()):.2f} %, median {100 * now.abs().median():.2f} -> "
              f"{100 * mean.abs().median():.2f} %")


def shape_and_sampling(d):
    w = d[d.scored == "white"].copy()
    w["score"] = w.apply(lambda r: delta_score(r, "68"), axis=1)
    w["family"] = w["shape"].str.split().str[0]
    w["set"] = np.where(w.file.str.startswith("held-out-26"), "held-out 26", "held-outs 20-24")
    table = w.groupby(["family", "rows", "set"])["score"].quantile(0.6827).unstack("set")
    print("2. δ_x's 68.27 % score quantile at 0.06-0.14 % white noise, by family and rows")
    print(table.round(2).to_string())


def white_read_as_walk(d):
    w = d[d.group.str.startswith("white") & (d.scored == "random walk") & (d.noise_read == "random walk")]
    covered = {level: np.mean([delta_score(r, level) <= factor for _, r in w.iterrows()])
               for level, factor in zip(("68", "95"), WALK_FACTORS)}
    print(f"3. White noise at 0.06-0.1 % read as a walk (held-outs 20-24): {len(w)} of {len(d)} accepted curves, "
          f"rows {sorted(w.rows.unique())}; δ_x covered {100 * covered['68']:.1f} % at 68 %, "
          f"{100 * covered['95']:.1f} % at 95 %")
    print(w.groupby("shape").size().to_string())


def main(argv):
    folder = pathlib.Path(argv[1] if len(argv) > 1 else pathlib.Path(__file__).resolve().parent / "results" /
                          "calibration")
    replicates_mean(accepted([folder / f for f in HELD_OUT]))
    shape_and_sampling(accepted([folder / f for f in LOW + ["held-out-26-low-all.csv"]]))
    white_read_as_walk(accepted([folder / f for f in LOW]))


if __name__ == "__main__":
    main(sys.argv)
