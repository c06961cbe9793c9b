#!/usr/bin/env python3
"""The bootstrap's half-bias correction on random-walk curves, with and without (docs/analysis.md,
"The bootstrap's bias on a random walk").

Usage: bias_correction.py compare [--raw-files A.csv,B.csv] FILE.csv [FILE.csv ...]
       bias_correction.py shift {add|remove} IN.csv OUT.csv

The files are per-curve output of bench/analysis_calibration. On a curve read as a random walk the
estimate and every interval bound move together by half the bootstrap's bias b (the sd keeps b/2 as
error either way), so a file written with half of b subtracted ("corrected") gives the numbers
without the subtraction ("raw") by adding b/2, and back.

compare: treats each file as it was written under the analysis that wrote it (--raw-files names the
files written without the subtraction; the others are taken as corrected) and prints, on its
accepted random-walk curves, both variants side by side: mean and rms of z = (δ_x − truth)/sd, δ_x's
rms and mean relative error, and, where the file carries x_c_bias and x_p_bias, the 95 % coverage of
x_c and x_p (± 1.96 sd).
shift add: writes IN with δ_x and its bounds (and x_c, x_p where their biases are given) moved by
+b/2 on random-walk curves (corrected → raw); shift remove: by −b/2 (raw → corrected). The output
feeds bench/interval_scales.py.
Standard library only.
"""
import csv
import math
import sys

MOVED = {"delta_x_bias": ("delta_x", "ci68_low", "ci68_high", "ci95_low", "ci95_high"),
         "x_c_bias": ("x_c",), "x_p_bias": ("x_p",)}


def is_walk(row):
    return row["accepted"] == "1" and row["noise"] == "random walk"


def moved(row, sign):
    row = dict(row)
    if not is_walk(row):
        return row
    for bias, columns in MOVED.items():
        if row.get(bias, "") == "":
            continue
        half = 0.5 * sign * float(row[bias])
        for column in columns:
            row[column] = repr(float(row[column]) + half)
    return row


def read(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"{path}: cannot read it ({e.strerror}); name an existing per-curve file")


def summary(rows):
    walk = [r for r in rows if is_walk(r)]
    z, err = [], []
    cover = {"x_c": 0, "x_p": 0}
    has_strain_bias = bool(walk) and walk[0].get("x_c_bias", "") != ""
    for r in walk:
        truth = float(r["delta_x_true"])
        z.append((float(r["delta_x"]) - truth) / float(r["delta_x_sd"]))
        err.append((float(r["delta_x"]) - truth) / truth)
        for name in cover:
            cover[name] += abs(float(r[name]) - float(r[name + "_true"])) <= 1.96 * float(r[name + "_sd"])
    n = len(walk)
    if n == 0:
        return "no accepted random-walk curves"
    text = (f"{n} curves; mean z {sum(z) / n:+.3f}, rms z {math.sqrt(sum(v * v for v in z) / n):.3f}; "
            f"δ_x rms error {100 * math.sqrt(sum(e * e for e in err) / n):.2f} %, mean {100 * sum(err) / n:+.2f} %")
    if has_strain_bias:
        text += f"; x_c 95 % {100 * cover['x_c'] / n:.1f} %, x_p 95 % {100 * cover['x_p'] / n:.1f} %"
    return text


def main():
    args = sys.argv[1:]
    if len(args) >= 2 and args[0] == "compare":
        raw_files = set()
        files = []
        rest = args[1:]
        while rest:
            if rest[0] == "--raw-files":
                raw_files.update(rest[1].split(","))
                rest = rest[2:]
            else:
                files.append(rest[0])
                rest = rest[1:]
        for path in files:
            rows = read(path)
            raw = rows if path in raw_files else [moved(r, +1) for r in rows]
            corrected = [moved(r, -1) for r in rows] if path in raw_files else rows
            print(f"{path}\n  half subtracted: {summary(corrected)}\n  none subtracted: {summary(raw)}")
    elif len(args) == 4 and args[0] == "shift" and args[1] in ("add", "remove"):
        rows = read(args[2])
        sign = +1 if args[1] == "add" else -1
        with open(args[3], "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            writer.writeheader()
            writer.writerows(moved(r, sign) for r in rows)
    else:
        sys.exit(__doc__.split("\n\n")[1])


if __name__ == "__main__":
    main()
