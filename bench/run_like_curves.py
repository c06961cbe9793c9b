#!/usr/bin/env python3
"""Known-answer curves written as `rupture run` writes them, analysed by `rupture analyze` as they are
and on a grid aligned with their rows (docs/analysis.md, "On DEM runs").

Usage: run_like_curves.py RUPTURE K NOISE ROWS_EVERY SEEDS [WORKDIR]
       run_like_curves.py --lattice CURVES.csv OUT.csv   (any table with a strain[...] column, such as a
                                                       run's curves.csv: OUT holds it on the rows' lattice)

Weibull ELS curves F = x exp(-x^K), E_e = F x / 2, with white noise of NOISE (a share of each peak)
on each, a row every ROWS_EVERY steps of a plate that starts smoothly (strain ∝ steps² over the first
10,000 of 100,000 steps) and a last row where the run stopped (step 100,037, off the rows' lattice).
Each curve is analysed twice: as written (rupture resamples the uneven curve) and on the rows' own
lattice (the even rows as they are, the smooth start interpolated; the stop row left out), prepared
here, so that rupture sees a uniform curve. Prints acceptance, x_p's and δ_x's rms relative errors
and δ_x's interval coverage for both. Needs numpy.
"""
import json
import pathlib
import shutil
import subprocess
import sys

import numpy as np

from curve_table import column_index, read_table


def lattice_grid(x, columns):
    """The columns on the lattice of the spacing most rows share (anchored on the first even row)."""
    spacing = np.diff(x)
    step = np.median(spacing)
    even = np.abs(spacing - step) <= 1e-6 * step
    anchor = x[int(np.argmax(even))]
    first = int(np.ceil((x[0] - anchor) / step - 1e-9))
    last = int(np.floor((x[-1] - anchor) / step + 1e-9))
    grid = anchor + np.arange(first, last + 1) * step
    return grid, [np.interp(grid, x, c) for c in columns]


def write_on_lattice(source, target):
    """A comma-separated table with a strain[...] column, '#' comment lines kept, on its rows' lattice."""
    table = read_table(source)
    strain = column_index(table, source, "strain")
    rows = np.array(table.rows)
    grid, columns = lattice_grid(rows[:, strain], [rows[:, c] for c in range(rows.shape[1])])
    columns[strain] = grid
    with open(target, "w", encoding="utf-8") as f:
        f.write("\n".join(table.comments + [",".join(table.names)]) + "\n")
        for row in zip(*columns):
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    print(f"{target}: {len(table.rows)} rows -> {len(grid)} on the rows' lattice")


def write(path, x, force, energy):
    with open(path, "w", encoding="utf-8") as f:
        f.write("strain[1],force[1],elastic_energy[1]\n")
        for row in zip(x, force, energy):
            f.write("%r,%r,%r\n" % row)


def analyse(rupture, path, document, script):
    """`rupture analyze PATH -o DOCUMENT`: its analysis.json, or None where the curve was rejected."""
    done = subprocess.run([rupture, "analyze", str(path), "-o", str(document)], capture_output=True, text=True,
                          check=False)
    if done.returncode not in (0, 4):  # 4: analysed and rejected
        sys.exit(f"{script}: {rupture} analyze {path} failed ({done.returncode}): {done.stderr.strip()}; give "
                 "the path of a built rupture")
    j = json.loads(pathlib.Path(document).read_text(encoding="utf-8"))
    return j if j["accepted"] else None


def main(argv):
    rupture, k, noise, every, seeds = argv[1], float(argv[2]), float(argv[3]), int(argv[4]), int(argv[5])
    if not shutil.which(rupture):
        sys.exit(f"run_like_curves.py: no program '{rupture}'; give the path of a built rupture, e.g. "
                 "build/release/bin/rupture")
    work = pathlib.Path(argv[6] if len(argv) > 6 else "/tmp/run-like-curves")
    work.mkdir(parents=True, exist_ok=True)
    force = lambda x: x * np.exp(-x ** k)
    energy = lambda x: 0.5 * x * force(x)
    rate = lambda x: force(x) * (1 - 0.5 * k * x ** k)
    x_c = (1 / k) ** (1 / k)
    fine = np.linspace(1e-4, 3.0, 2_000_001)
    x_p = fine[np.argmax(rate(fine))]
    F_c, E_max = force(x_c), energy(fine).max()
    ramp, stop = 10_000, 100_037
    speed = 1.6 * x_c / (stop - ramp / 2)
    steps = np.append(np.arange(0, 100_001, every), stop).astype(float)
    x = np.where(steps < ramp, speed * steps ** 2 / (2 * ramp), speed * (steps - ramp / 2))
    delta = x_c - x_p
    results = {"as written": [], "rows' lattice": []}
    stems = {"as written": "written", "rows' lattice": "lattice"}
    for seed in range(seeds):
        rng = np.random.default_rng(seed)
        f = force(x) + noise * F_c * rng.standard_normal(len(x))
        e = energy(x) + noise * E_max * rng.standard_normal(len(x))
        grid, (gf, ge) = lattice_grid(x, [f, e])
        for kind, (xs, fs, es) in (("as written", (x, f, e)), ("rows' lattice", (grid, gf, ge))):
            path = work / f"{stems[kind]}-{seed}.csv"
            document = work / f"{stems[kind]}-{seed}.json"
            write(path, xs, fs, es)
            results[kind].append(analyse(rupture, path, document, "run_like_curves.py"))
    print(f"Weibull k = {k:g}, white noise {100 * noise:g} %, a row every {every} steps ({len(x)} rows), "
          f"{seeds} seeds")
    print("| grid | accepted | x_p rms error | δ_x rms error | δ_x 68 % / 95 % covered |\n|---|---|---|---|---|")
    for kind, found in results.items():
        ok = [j for j in found if j]
        if not ok:
            print(f"| {kind} | 0 | | | |")
            continue
        xp = np.array([(j["x_p"]["value"] - x_p) / x_p for j in ok])
        dx = np.array([(j["delta_x"]["value"] - delta) / delta for j in ok])
        c68 = np.mean([j["delta_x"]["ci68"][0] <= delta <= j["delta_x"]["ci68"][1] for j in ok])
        c95 = np.mean([j["delta_x"]["ci95"][0] <= delta <= j["delta_x"]["ci95"][1] for j in ok])
        print(f"| {kind} | {len(ok)} | {100 * np.sqrt(np.mean(xp ** 2)):.1f} % | "
              f"{100 * np.sqrt(np.mean(dx ** 2)):.1f} % | {100 * c68:.0f} / {100 * c95:.0f} % |")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--lattice":
        write_on_lattice(sys.argv[2], sys.argv[3])
    elif len(sys.argv) < 6:
        sys.exit(__doc__)
    else:
        main(sys.argv)
