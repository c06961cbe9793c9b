"""bench/run_like_curves.py: the grid on the rows' own lattice keeps a run's even rows as they are and
leaves out only what lies off the lattice (docs/analysis.md, "On DEM runs")."""

import numpy as np

import bench_scripts

def load():
    return bench_scripts.load("run_like_curves")


def test_the_lattice_grid_keeps_the_even_rows_and_drops_the_stop_row():
    module = load()
    steps = np.append(np.arange(0, 100_001, 200), 100_037).astype(float)
    x = np.where(steps < 10_000, 1e-5 * steps ** 2 / 20_000, 1e-5 * (steps - 5_000))
    values = np.random.default_rng(1).standard_normal(len(x))
    grid, (on_grid,) = module.lattice_grid(x, [values])
    assert np.allclose(np.diff(grid), 200e-5, rtol=1e-9, atol=0)
    assert grid[-1] <= x[-1] and abs(grid[-1] - x[-2]) < 1e-12, "ends on the last even row, not the stop row"
    even = steps >= 10_000
    even &= steps <= 100_000
    rows = np.searchsorted(grid, x[even] - 1e-12)
    assert np.allclose(on_grid[rows], values[even], rtol=0, atol=1e-9), "even rows taken as they are"
    # 0 to 0.95 in steps of 0.002: the smooth start covers half the strain of as many even steps.
    assert len(grid) == 476
