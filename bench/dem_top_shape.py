#!/usr/bin/env python3
"""How a DEM run's force and elastic energy top out (docs/analysis.md, "Known answers with a DEM-like top").

Usage: dem_top_shape.py DENSE_CURVES...

DENSE_CURVES are curves.csv files written with a row every few steps (`rupture run CONFIG --set
output.interval=10`). For each run: x_c, the strain where the running mean of the top force over 40 rows
peaks (between 0.3 and 0.5 % strain; bench/dem_x_c_reference.py averages that over 20 and 40 rows); where
the running mean of the elastic energy peaks and where the force first falls below 0.9 of its peak, both
over x_c; and the force's and energy's running means at 0.90 to 1.10 x_c, over their peaks. Standard
library only.
"""
import csv
import sys

WIDTH = 40
FRACTIONS = (0.90, 0.95, 0.98, 1.00, 1.02, 1.04, 1.06, 1.08, 1.10)


def running_means(path):
    try:
        f = open(path, encoding="utf-8")
    except OSError as e:
        sys.exit(f"{path}: cannot read it ({e.strerror}); name a curves.csv of rupture run")
    with f:
        reader = csv.reader(line for line in f if not line.startswith("#"))
        header = next(reader)
        column = lambda prefix: next((i for i, name in enumerate(header) if name.startswith(prefix)), None)
        columns = (column("strain["), column("force_top["), column("elastic_energy["))
        if None in columns:
            sys.exit(f"{path}: no strain, force_top or elastic_energy column; name a curves.csv of rupture run")
        rows = [[float(r[i]) for i in columns] for r in reader]
    if len(rows) < 2 * WIDTH:
        sys.exit(f"{path}: {len(rows)} rows; name a curves.csv written with a row every few steps")
    sums = [sum(r[k] for r in rows[:WIDTH]) for k in range(3)]
    means = [[s / WIDTH for s in sums]]
    for i in range(WIDTH, len(rows)):
        sums = [sums[k] + rows[i][k] - rows[i - WIDTH][k] for k in range(3)]
        means.append([s / WIDTH for s in sums])
    return means


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    print("| run | x_c [%] | E_e's peak / x_c | F < 0.9 F_c at / x_c | " +
          " | ".join(f"F, E_e at {f:.2f} x_c" for f in FRACTIONS) + " |")
    print("|---" * (4 + len(FRACTIONS)) + "|")
    for path in argv[1:]:
        means = running_means(path)
        loading = [m for m in means if 0.3 < m[0] < 0.5]
        if not loading:
            sys.exit(f"{path}: no rows between 0.3 and 0.5 % strain; name a run pulled past its peak")
        top = max(range(len(means)), key=lambda i: means[i][1] if 0.3 < means[i][0] < 0.5 else float("-inf"))
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
