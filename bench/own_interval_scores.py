#!/usr/bin/env python3
"""How the bootstrap's own intervals (factor 1) follow the errors, per group and, on curves that come
apart, by where the collapse comes (docs/analysis.md, "The bootstrap's noise read on the loading").

Usage: own_interval_scores.py FILE [BEFORE]

FILE (and BEFORE, the same curves from an earlier build, printed as BEFORE → FILE) are per-curve files
of bench/analysis_calibration. Per group: accepted curves; x_p's and x_c's ratio, their median sd over
their error's robust sd (half the 15.87-84.13 % quantile range; 1 when the sd follows the error); the
share of x_p's and x_c's errors within ± sd; δ_x's 68 % and 95 % coverage (the file's own intervals);
δ_x's rms relative error. Then, for the accepted curves of FILE with a collapse (`collapse_cut`), δ_x's,
x_c's and x_p's 68 % / 95 % coverage by the cut over the true x_c and by the kind of noise, scored as
bench/interval_scales.py scores (the 95 % interval holds the 68 % one). Standard library only.
"""
import csv
import importlib.util
import math
import pathlib
import statistics
import sys

spec = importlib.util.spec_from_file_location("interval_scales",
                                              pathlib.Path(__file__).with_name("interval_scales.py"))
interval_scales = importlib.util.module_from_spec(spec)
spec.loader.exec_module(interval_scales)

OWN = {"68": 1.0, "95": 1.0}
CUT_BANDS = ((1.0, 1.1), (1.1, 1.2), (1.2, 1.35), (1.35, 1.5))


def read(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            return [dict(r, source=path) for r in csv.DictReader(f)]
    except OSError as e:
        sys.exit(f"{path}: cannot read it ({e.strerror}); name a per-curve file of bench/analysis_calibration")


def robust_sd(values):
    q = statistics.quantiles(values, n=10000, method="inclusive")
    return (q[8412] - q[1586]) / 2.0


def covered(rows, quantity, level):
    interval_scales.QUANTITY = quantity
    return 100.0 * sum(interval_scales.is_covered(r, level, OWN) for r in rows) / len(rows)


def group_scores(rows):
    """{group: {score: value}} over each group's accepted curves, in the file's order."""
    groups = {}
    for r in rows:
        groups.setdefault(r["group"], []).append(r)
    scores = {}
    for name, members in groups.items():
        a = [r for r in members if r["accepted"] == "1"]
        s = {"accepted": len(a)}
        if len(a) > 2:
            for q in ("x_p", "x_c"):
                errors = [float(r[q]) - float(r[q + "_true"]) for r in a]
                sds = [float(r[q + "_sd"]) for r in a]
                s[q + " ratio"] = statistics.median(sds) / robust_sd(errors)
                s[q + " 68 %"] = 100.0 * sum(abs(e) < sd for e, sd in zip(errors, sds)) / len(a)
            s["δ_x 68 %"], s["δ_x 95 %"] = covered(a, "delta_x", "68"), covered(a, "delta_x", "95")
            s["δ_x rms %"] = 100.0 * math.sqrt(statistics.fmean(
                ((float(r["delta_x"]) - float(r["delta_x_true"])) / float(r["delta_x_true"])) ** 2 for r in a))
        scores[name] = s
    return scores


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    after = read(argv[1])
    before = group_scores(read(argv[2])) if len(argv) > 2 else {}
    columns = ("accepted", "x_p ratio", "x_p 68 %", "x_c ratio", "x_c 68 %", "δ_x 68 %", "δ_x 95 %", "δ_x rms %")
    print("| group | " + " | ".join(columns) + " |")
    print("|---" * (len(columns) + 1) + "|")
    for name, s in group_scores(after).items():
        cells = []
        for c in columns:
            now = s.get(c)
            was = before.get(name, {}).get(c)
            text = "-" if now is None else (f"{now:d}" if c == "accepted" else f"{now:.3g}")
            if was is not None:
                text = (f"{was:d}" if c == "accepted" else f"{was:.3g}") + " → " + text
            cells.append(text)
        print(f"| {name} | " + " | ".join(cells) + " |")
    cut = [r for r in after if r["accepted"] == "1" and r.get("collapse_cut")]
    if not cut:
        return 0
    print(f"\nCurves that come apart ({len(cut)} accepted), own intervals, 68 % / 95 % covered:\n")
    print("| cut at b x_c | noise | curves | δ_x | x_c | x_p |")
    print("|---|---|---|---|---|---|")
    for kind in ("white", "random walk", "both"):
        for low, high in CUT_BANDS + ((1.0, math.inf),):
            rows = [r for r in cut if (kind == "both" or r["noise"] == kind)
                    and low <= float(r["collapse_cut"]) / float(r["x_c_true"]) < high]
            if not rows:
                continue
            band = "all" if high == math.inf else f"{low:g}-{high:g}"
            cells = [f"{covered(rows, q, '68'):.1f} / {covered(rows, q, '95'):.1f} %" for q in ("delta_x", "x_c", "x_p")]
            print(f"| {band} | {kind} | {len(rows)} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
