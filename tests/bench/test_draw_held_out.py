"""bench/draw_held_out.py: a seed already drawn prints the rows calibration_set.hpp holds for it, and a
new seed draws no parameter an earlier set used (docs/analysis.md, "Calibration")."""
import pathlib
import subprocess
import sys

import bench_scripts

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "bench" / "draw_held_out.py"
SETS = (ROOT / "tests" / "analysis" / "calibration_set.hpp").read_text(encoding="utf-8")


def draw(seed):
    return subprocess.run([sys.executable, str(SCRIPT), str(seed)], capture_output=True, text=True,
                          check=True).stdout.splitlines()


def rows_of(seed):
    return [line for line in SETS.splitlines() if line.lstrip().startswith(f'{{"held-out-{seed}",')]


def test_a_drawn_seed_prints_its_rows_again():
    for seed in (17, 20, 23, 24):
        assert rows_of(seed), f"held-out-{seed} has no rows in calibration_set.hpp"
        assert draw(seed) == rows_of(seed)


def load():
    return bench_scripts.load("draw_held_out")


def parts(match):
    """Weibull k, α, σ, gamma k, the uniform law (a, b) and the mixture's name of a row."""
    return [float(match[2]), float(match[3]), float(match[6]), float(match[7]), (float(match[4]), float(match[5])),
            match[8]]


def test_earlier_shapes_are_the_tuning_sets_and_those_of_the_rows_before_the_seed():
    used = load().earlier_shapes(25)
    assert {2.0, 3.0, 5.0} <= used["weibull"] and (0.2, 1.0) in used["uniform"]  # the tuning set's
    assert "weibull mixture" in used["mixture"]
    assert (0.18, 0.93) in used["uniform"]  # held-out 18's, repeated by held-out 24
    assert 4.1 in used["alpha"] and "weibull mixture k=5.7 45/55 x1.6" in used["mixture"]  # held-out 24's
    used = load().earlier_shapes(18)
    assert (0.18, 0.93) not in used["uniform"]
    assert 4.1 not in used["alpha"] and "weibull mixture k=5.7 45/55 x1.6" not in used["mixture"]


def test_new_seeds_reuse_no_earlier_parameter_or_shape():
    row = load().ROW
    used = [set() for _ in range(6)]
    for match in row.finditer(SETS):
        for family, value in enumerate(parts(match)):
            used[family].add(value)
    latest = max(int(m[1]) for m in row.finditer(SETS))
    for seed in range(latest + 1, latest + 41):
        fresh = draw(seed)
        assert len(fresh) == 2
        for line in fresh:
            for family, value in enumerate(parts(row.match(line.strip()))):
                assert value not in used[family], line


def test_a_range_whose_two_digit_values_are_all_taken_draws_at_three_digits():
    # σ's 41 two-digit values in [0.2, 0.6] were all taken by held-out 28: every later seed draws it
    # at three digits (before, the draw looped for ever).
    taken = {round(0.2 + 0.01 * i, 2) for i in range(41)}
    assert taken <= load().earlier_shapes(29)["sigma"]
    row = load().ROW
    for seed in (29, 30):
        for line in draw(seed):
            sigma = float(row.match(line.strip())[6])
            assert 0.2 <= sigma <= 0.6 and sigma not in taken and len(f"{sigma:g}") == 5, line
