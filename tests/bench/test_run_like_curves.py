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


def test_a_runs_table_is_written_on_its_lattice_with_its_comments_and_columns(tmp_path):
    steps = np.append(np.arange(0, 20_001, 200), 20_037).astype(float)
    strain = np.where(steps < 2_000, 1e-5 * steps ** 2 / 4_000, 1e-5 * (steps - 1_000))
    source = tmp_path / "curves.csv"
    lines = ["# rupture run", "step[1],strain[%],force_top[N]"]
    lines += [f"{int(s)},{x!r},{2.0 * x!r}" for s, x in zip(steps, strain)]
    source.write_text("\n".join(lines) + "\n", encoding="utf-8")
    target = tmp_path / "lattice.csv"
    load().write_on_lattice(source, target)
    written = target.read_text(encoding="utf-8").splitlines()
    assert written[:2] == lines[:2]
    rows = np.array([[float(v) for v in line.split(",")] for line in written[2:]])
    assert np.allclose(np.diff(rows[:, 1]), 200e-5, rtol=1e-9, atol=0)
    assert np.allclose(rows[:, 2], 2.0 * rows[:, 1]), "every column interpolated at the grid's strains"
    assert abs(rows[-1, 0] - 20_000) < 1e-6, "the stop row is left out"


def test_a_table_without_strain_is_refused_with_the_fix(tmp_path):
    source = tmp_path / "bad.csv"
    source.write_text("step[1],force[N]\n0,0\n1,1\n", encoding="utf-8")
    try:
        load().write_on_lattice(source, tmp_path / "out.csv")
    except SystemExit as refusal:
        assert "no column 'strain'" in str(refusal) and "bad.csv" in str(refusal)
    else:
        raise AssertionError("a table without strain was written")
