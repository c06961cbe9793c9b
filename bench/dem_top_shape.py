#!/usr/bin/env python3
"""How a DEM run's force and elastic energy top out (docs/analysis.md, "Known answers with a DEM-like top").

Usage: dem_top_shape.py [--top-range LOW,HIGH] [--width ROWS] DENSE_CURVES...

DENSE_CURVES are curves.csv files written with a row every few steps (`rupture run CONFIG --set
output.interval=10`). For each run: x_c, the strain where the running mean of the top force over ROWS rows
(default 40) peaks (between LOW and HIGH % strain, default 0.3 and 0.5, the default study's;
bench/dem_x_c_reference.py averages that over 20 and 40 rows); where
the running mean of the elastic energy peaks and where the force first falls below 0.9 of its peak, both
over x_c; and the force's and energy's running means at 0.90 to 1.10 x_c, over their peaks. Standard
library only.
"""
import sys

from curve_table import read_columns
from dense_rows import found_force_top, no_other_options, parse_rows, take_option, take_top_range, window_means

FRACTIONS = (0.90, 0.95, 0.98, 1.00, 1.02, 1.04, 1.06, 1.08, 1.10)


def running_means(path, width):
    rows = read_columns(path, ("strain", "force_top", "elastic_energy"))
    if len(rows) < 2 * width:
        sys.exit(f"{path}: {len(rows)} rows; name a curves.csv written with a row every few steps")
    return window_means(rows, width)


def main(argv):
    args = argv[1:]
    low, high = take_top_range(args)
    width = parse_rows(take_option(args, "--width", "40"), "--width")
    no_other_options(args, ("--top-range", "--width"))
    if not args:
        sys.exit(__doc__)
    print("| run | x_c [%] | E_e's peak / x_c | F < 0.9 F_c at / x_c | " +
          " | ".join(f"F, E_e at {f:.2f} x_c" for f in FRACTIONS) + " |")
    print("|---" * (4 + len(FRACTIONS)) + "|")
    for path in args:
        means = running_means(path, width)
        top = found_force_top(means, low, high, path)
        x_c, F_c = means[top][0], means[top][1]
        energy_top = max(range(len(means)), key=lambda i: means[i][2])
        E_max = means[energy_top][2]
        fall = next((means[i][0] for i in range(top, len(means)) if means[i][1] < 0.9 * F_c), float("nan"))
        cells = []
        for fraction in FRACTIONS:
            near = min(means, key=lambda m: abs(m[0] - fraction * x_c))
            cells.append(f"{near[1] / F_c:.3f}, {near[2] / E_max:.3f}")
        print(f"| {path} | {x_c:.4f} | {means[energy_top][0] / x_c:.3f} | {fall / x_c:.3f} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
