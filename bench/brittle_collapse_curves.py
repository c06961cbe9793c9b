#!/usr/bin/env python3
"""Known-answer curves of a brittle collapse, analysed by `rupture analyze` (docs/analysis.md, "A collapse
the filter cannot follow").

Usage: brittle_collapse_curves.py RUPTURE K B FORCE_NOISE ENERGY_NOISE ROWS SEEDS [WORKDIR]

Weibull ELS curves F = x exp(-x^K), E_e = F x / 2 on ROWS uniform rows up to 1.5 x_c, which fall by e
every 3 rows from B x_c on (a brittle sample breaking apart), with white noise of FORCE_NOISE (share of
F_c) on F and ENERGY_NOISE (share of E_max) on E_e. Prints acceptance, x_p's mean and rms error, x_c's
rms error, δ_x's mean, rms error and interval coverage, and the mean cutoff. Needs numpy.
"""
import pathlib
import shutil
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import run_like_curves  # noqa: E402  (a sibling script: its writer and its call of rupture analyze)

E_FOLD_ROWS = 3


def curves(k, b, rows):
    """Strains, exact force and energy of the cut curve, and the truth (x_p, x_c)."""
    force = lambda x: x * np.exp(-x ** k)
    energy = lambda x: 0.5 * x * force(x)
    rate = lambda x: force(x) * (1 - 0.5 * k * x ** k)
    x_c = (1 / k) ** (1 / k)
    fine = np.linspace(1e-4, b * x_c, 2_000_001)
    x_p = fine[np.argmax(rate(fine))]
    x = np.linspace(0, 1.5 * x_c, rows)
    cut = b * x_c
    fall = np.where(x > cut, np.exp(-(x - cut) / (E_FOLD_ROWS * (x[1] - x[0]))), 1.0)
    held = np.minimum(x, cut)
    return x, force(held) * fall, energy(held) * fall, x_p, x_c


def main(argv):
    rupture, k, b = argv[1], float(argv[2]), float(argv[3])
    force_noise, energy_noise, rows, seeds = float(argv[4]), float(argv[5]), int(argv[6]), int(argv[7])
    if not shutil.which(rupture):
        sys.exit(f"brittle_collapse_curves.py: no program '{rupture}'; give the path of a built rupture, e.g. "
                 "build/release/bin/rupture")
    work = pathlib.Path(argv[8] if len(argv) > 8 else "/tmp/brittle-collapse-curves")
    work.mkdir(parents=True, exist_ok=True)
    x, f0, e0, x_p, x_c = curves(k, b, rows)
    delta = x_c - x_p
    found = []
    for seed in range(seeds):
        rng = np.random.default_rng(seed)
        f = f0 + force_noise * f0.max() * rng.standard_normal(rows)
        e = e0 + energy_noise * e0.max() * rng.standard_normal(rows)
        path = work / f"collapse-{seed}.csv"
        run_like_curves.write(path, x, f, e)
        found.append(run_like_curves.analyse(rupture, path, work / f"collapse-{seed}.json",
                                             "brittle_collapse_curves.py"))
    ok = [j for j in found if j]
    print(f"Weibull k = {k:g} cut at {b:g} x_c, F noise {100 * force_noise:g} %, E_e noise "
          f"{100 * energy_noise:g} %, {rows} rows: truth x_p = {x_p:.4f}, x_c = {x_c:.4f}, δ_x = {delta:.4f}; "
          f"accepted {len(ok)} of {seeds}")
    if not ok:
        return
    xp = np.array([j["x_p"]["value"] for j in ok])
    xc = np.array([j["x_c"]["value"] for j in ok])
    dx = np.array([j["delta_x"]["value"] for j in ok])
    c68 = np.mean([j["delta_x"]["ci68"][0] <= delta <= j["delta_x"]["ci68"][1] for j in ok])
    c95 = np.mean([j["delta_x"]["ci95"][0] <= delta <= j["delta_x"]["ci95"][1] for j in ok])
    rms = lambda v, t: 100 * np.sqrt(np.mean(((v - t) / t) ** 2))
    cutoff = np.mean([j["filter"]["cutoff_nyquist"] for j in ok])
    print(f"  x_p mean {xp.mean():.4f}, rms error {rms(xp, x_p):.1f} %; x_c rms error {rms(xc, x_c):.2f} %; "
          f"δ_x mean {dx.mean():.4f}, rms error {rms(dx, delta):.1f} %, 68 / 95 % covered "
          f"{100 * c68:.0f} / {100 * c95:.0f} %; cutoff {cutoff:.3f}")


if __name__ == "__main__":
    if len(sys.argv) < 8:
        sys.exit(__doc__)
    main(sys.argv)
