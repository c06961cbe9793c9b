#!/usr/bin/env python3
"""Draws a twelve-shape held-out set for the calibration (tests/analysis/calibration_set.hpp).

Usage: draw_held_out.py SEED

Prints two rows of `later_held_out_sets` named held-out-SEED: each parameter drawn with
random.Random(SEED) within its family's range, rounded to two significant digits, drawn again where
that value already names a shape of an earlier set (the test
CalibrationSets.HeldOutSetsAreDisjointAndFoundByName checks the names). USED below lists every
set's values; those of held-out-SEED and later (read from calibration_set.hpp's rows) are taken out
before drawing, so a seed already drawn prints its rows again. From held-out 25 on, a uniform law
or a mixture whose name an earlier set holds is drawn again too (held-out 24, drawn before, repeats
held-out 18's uniform [0.18, 0.93]). Uniform laws [a, b] have
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

# The parameters the tuning set and held-outs 1-24 already use (their shape names).
USED = {
    "weibull": {2, 3, 5, 1.5, 2.5, 4, 6, 3.5, 1.8, 2.2, 1.6, 2.8, 3.2, 2.4, 4.4, 2.6, 5.8, 4.7, 3.1, 2.1, 3.8, 2.9, 2.3, 4.5, 3.3, 3.9, 5.6, 3.4, 4.6, 4.1, 5.5, 1.7, 5.7, 1.9, 5.3, 4.9},
    "alpha": {-0.5, 3, 10, 6, 1, 2, 5, 0.5, 4, 7, 8, 1.5, 2.5, 3.5, 4.5, 5.5, -0.38, 2.4, 3.9, 7.3, 9.6, 8.4, 6.4, 7.8, 1.1, 3.6, 6.7, 6.1, 6.2, 0.23, 1.9, 8.8, 9.5, 4.9, 1.4, 4.1},
    "sigma": {0.3, 0.5, 0.2, 0.4, 0.6, 0.35, 0.25, 0.45, 0.55, 0.7, 0.38, 0.42, 0.32, 0.48, 0.59, 0.54,
              0.46, 0.58, 0.24, 0.22, 0.39, 0.29, 0.33, 0.37, 0.56, 0.23, 0.52, 0.21, 0.44, 0.28, 0.41, 0.51, 0.47, 0.26},
    "gamma": {4, 8, 2.5, 1.5, 3, 5, 6, 3.5, 2, 4.5, 7, 5.5, 3.8, 2.1, 7.2, 3.6, 7.4, 2.2, 6.9, 4.7, 3.4, 2.6, 6.4, 5.4, 3.1, 6.8, 2.7, 7.6, 7.1, 2.8, 5.9, 6.5, 5.3},
}


SETS = pathlib.Path(__file__).resolve().parent.parent / "tests" / "analysis" / "calibration_set.hpp"
ROW = re.compile(r'\{"held-out-(\d+)", ([-\d.]+), ([-\d.]+), ([-\d.]+), ([-\d.]+), ([-\d.]+), ([-\d.]+), '
                 r'\{"([^"]+)"')
FIRST_SEED_CHECKING_EVERY_NAME = 25


def drawn_from(seed):
    """{family: values} of the rows of held-out-SEED and later in calibration_set.hpp."""
    drawn = {family: set() for family in USED}
    for match in ROW.finditer(SETS.read_text(encoding="utf-8")):
        if int(match[1]) >= seed:
            for family, group in (("weibull", 2), ("alpha", 3), ("sigma", 6), ("gamma", 7)):
                drawn[family].add(float(match[group]))
    return drawn


def earlier_names(seed):
    """The uniform laws (a, b) and mixture names of the tuning set and of the rows before
    held-out-SEED."""
    uniforms, mixtures = {(0.2, 1.0)}, {"weibull mixture"}
    for match in ROW.finditer(SETS.read_text(encoding="utf-8")):
        if int(match[1]) < seed:
            uniforms.add((float(match[4]), float(match[5])))
            mixtures.add(match[8])
    return uniforms, mixtures


def two_digits(x):
    return float(f"{x:.2g}")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: draw_held_out.py SEED")
    seed = int(sys.argv[1])
    for family, values in drawn_from(seed).items():
        USED[family] -= values
    uniforms, mixtures = earlier_names(seed) if seed >= FIRST_SEED_CHECKING_EVERY_NAME else (set(), set())
    rng = random.Random(seed)

    def draw(family, low, high):
        while True:
            value = two_digits(rng.uniform(low, high))
            if family is None or value not in USED[family]:
                if family:
                    USED[family].add(value)
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
