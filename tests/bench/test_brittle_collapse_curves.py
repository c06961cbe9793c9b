"""bench/brittle_collapse_curves.py: the cut Weibull curves hold the closed forms up to the cut and fall by
e every 3 rows after it; the truth is that of the uncut law (docs/analysis.md, "A collapse the filter
cannot follow")."""

import numpy as np

import bench_scripts


def test_the_curve_is_the_weibull_law_up_to_the_cut_and_falls_by_e_every_three_rows():
    module = bench_scripts.load("brittle_collapse_curves")
    x, force, energy, x_p, x_c = module.curves(3.0, 1.2, 500)
    assert abs(x_c - 3.0 ** (-1.0 / 3.0)) < 1e-12
    # ℰ = e^(-x^3) (x - 1.5 x^4) is largest where its derivative vanishes: 1 - 9 x^3 + 4.5 x^6 = 0.
    assert abs(x_p - ((9 - np.sqrt(63)) / 9) ** (1 / 3)) < 2e-6
    assert abs(x[-1] - 1.5 * x_c) < 1e-12 and len(x) == 500
    before = x <= 1.2 * x_c
    assert np.allclose(force[before], x[before] * np.exp(-x[before] ** 3), rtol=1e-14, atol=0)
    assert np.allclose(energy, 0.5 * np.minimum(x, 1.2 * x_c) * force, rtol=1e-14, atol=0)
    after = np.flatnonzero(~before)
    assert np.allclose(force[after[3:]] / force[after[:-3]], np.exp(-1.0), rtol=1e-9, atol=0)
