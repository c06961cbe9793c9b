"""bench/structure_function.py: white noise, a random walk and a ringing each give their own
structure function, and a file without the named column is refused (docs/analysis.md)."""
import math
import random
import subprocess
import sys

import bench_scripts

SCRIPT = bench_scripts.path("structure_function")


def load():
    return bench_scripts.load("structure_function")


def test_white_noise_is_flat_and_a_walk_grows_as_the_lag():
    module = load()
    rng = random.Random(1)
    white = [rng.gauss(0.0, 1.0) for _ in range(20000)]
    walk = list(white)
    for i in range(1, len(walk)):
        walk[i] += walk[i - 1]
    for lag, ratio in zip(module.LAGS, module.ratios(white, 0, len(white))):
        assert abs(ratio - 1.0) < 0.05, (lag, ratio)
    # A walk's second differences at lag L hold 2L steps: S(L) = 2L sigma^2, so S(L)/S(1) = L.
    for lag, ratio in zip(module.LAGS, module.ratios(walk, 0, len(walk))):
        assert abs(ratio / lag - 1.0) < 0.1, (lag, ratio)
    assert module.ringing_period(module.ratios(white, 0, len(white))) is None


def test_a_ringing_dips_at_its_period():
    module = load()
    rng = random.Random(2)
    ringing = [math.sin(2.0 * math.pi * i / 4.0 + 0.3) + 0.01 * rng.gauss(0.0, 1.0) for i in range(4000)]
    r = module.ratios(ringing, 0, len(ringing))
    assert r[module.LAGS.index(4)] < 0.01
    assert module.ringing_period(r) == 4


def test_a_missing_column_is_refused_naming_the_header(tmp_path):
    curve = tmp_path / "curves.csv"
    curve.write_text("strain[%],force[N]\n0,0\n1,1\n")
    done = subprocess.run([sys.executable, str(SCRIPT), str(curve)], capture_output=True, text=True)
    assert done.returncode != 0
    assert "no column 'force_top' (the header has strain, force)" in done.stderr
