#!/usr/bin/env python3
"""Draws a twelve-shape held-out set for the calibration (tests/analysis/calibration_set.hpp).

Usage: draw_held_out.py SEED

Prints two rows of `later_held_out_sets` named held-out-SEED: each parameter drawn with
random.Random(SEED) within its family's range, rounded to two significant digits, drawn again where
that value already names a shape of an earlier set: the tuning set's or one of the rows before
held-out-SEED in calibration_set.hpp (the test CalibrationSets.HeldOutSetsAreDisjointAndFoundByName
checks the names), and drawn at three significant digits where every two-digit value of the range is
taken. Only earlier rows count, so a seed already drawn prints its rows again. From held-out 25 on, a uniform law or a mixture whose name an earlier set holds is drawn again too
(held-out 24, drawn before, repeats held-out 18's uniform [0.18, 0.93]). Uniform laws [a, b] have
a = b * U(0.03, 0.2), so ℰ's maximum is inside (a < 0.211 b); a mixture is recorded to its strong
part's 99.9 % quantile. Held-outs 17 to 24 were drawn by this script;
held-outs 15 and 16 by the same ranges in an earlier form.
Standard library only.
"""
import math
import pathlib
import random
import re
import sys

SETS = pathlib.Path(__file__).resolve().parent.parent / "tests" / "analysis" / "calibration_set.hpp"
# A row of later_held_out_sets: set, Weibull k, α, uniform a and b, σ, gamma k, the mixture's name.
ROW = re.compile(r'\{"held-out-(\d+)", ([-\d.]+), ([-\d.]+), ([-\d.]+), ([-\d.]+), ([-\d.]+), ([-\d.]+), '
                 r'\{"([^"]+)"')
FIRST_SEED_CHECKING_EVERY_NAME = 25
# Draws at two significant digits before a family counts as exhausted there (a range with one fresh
# value in 41 misses it in 10,000 draws with probability 2e-108).
TRIES_AT_TWO_DIGITS = 10_000


def earlier_shapes(seed):
    """{family: values} of the tuning set (calibration_set.hpp's shapes()) and of the rows before
    held-out-SEED; "uniform" holds (a, b) pairs, "mixture" names."""
    used = {"weibull": {2.0, 3.0, 5.0}, "alpha": {-0.5, 3.0, 10.0}, "sigma": {0.3}, "gamma": set(),
            "uniform": {(0.2, 1.0)}, "mixture": {"weibull mixture"}}
    for match in ROW.finditer(SETS.read_text(encoding="utf-8")):
        if int(match[1]) < seed:
            for family, group in (("weibull", 2), ("alpha", 3), ("sigma", 6), ("gamma", 7)):
                used[family].add(float(match[group]))
            used["uniform"].add((float(match[4]), float(match[5])))
            used["mixture"].add(match[8])
    return used


def two_digits(x):
    return float(f"{x:.2g}")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: draw_held_out.py SEED")
    seed = int(sys.argv[1])
    used = earlier_shapes(seed)
    every_name = seed >= FIRST_SEED_CHECKING_EVERY_NAME
    uniforms = used["uniform"] if every_name else set()
    mixtures = used["mixture"] if every_name else set()
    rng = random.Random(seed)

    def draw(family, low, high):
        # Two significant digits while the range has a fresh one; σ's 41 values in [0.2, 0.6] were all
        # used by held-out 28, so a range searched that long without one is drawn at three digits.
        for _ in range(TRIES_AT_TWO_DIGITS):
            value = two_digits(rng.uniform(low, high))
            if value not in used[family]:
                used[family].add(value)
                return value
        while True:
            value = float(f"{rng.uniform(low, high):.3g}")
            if value not in used[family]:
                used[family].add(value)
                return value

    for _ in range(2):
        k = draw("weibull", 1.5, 6)
        alpha = draw("alpha", -0.5, 10)
        while True:
            b = two_digits(rng.uniform(0.45, 1))
            a = two_digits(b * rng.uniform(0.03, 0.2))
            if (a, b) not in uniforms:
                uniforms.add((a, b))
                break
        sigma = draw("sigma", 0.2, 0.6)
        gamma = draw("gamma", 2, 8)
        while True:
            weak = two_digits(rng.uniform(0.3, 0.7))
            mixture_k = two_digits(rng.uniform(3, 6))
            scale = two_digits(rng.uniform(1.25, 1.6))
            share = round(weak * 100)
            name = f"weibull mixture k={mixture_k:g} {share}/{100 - share} x{scale:g}"
            if name not in mixtures:
                mixtures.add(name)
                break
        x_end = two_digits(scale * math.log(1000) ** (1 / mixture_k))
        print(f'    {{"held-out-{seed}", {k:g}, {alpha:g}, {a:g}, {b:g}, {sigma:g}, {gamma:g}, '
              f'{{"{name}", {weak:g}, {mixture_k:g}, {scale:g}, {x_end:g}}}}},')


if __name__ == "__main__":
    main()
