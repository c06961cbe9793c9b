"""The fiber bundle model: ELS theory of any threshold distribution and finite bundles.

A distribution is named as on the command line: "uniform", "uniform:a=0.2,b=1", "powerlaw:alpha=2",
"weibull:k=2,lambda=1" or "file:PATH" (a list of thresholds). Quantities are per N kappa = 1: strain
without unit, force F/(N kappa), energies E/(N kappa).
"""
import numpy as np
import pandas as pd

from . import _rupture

_UNITS = {"strain": "1", "force": "1", "elastic_energy": "1", "damage_energy": "1", "energy_rate": "1",
          "broken_fraction": "1"}


def theory(dist):
    """The ELS maxima (N -> infinity): x_c, F_c, x_m, E_max, x_p, Erate_max, delta_x, Gamma, A_r, ..."""
    return _rupture.fbm_theory(dist)


def _frame(columns):
    frame = pd.DataFrame(columns)
    frame.attrs["units"] = dict(_UNITS)
    frame.attrs["note"] = "per N kappa = 1: strain, F/(N kappa), E/(N kappa), dE_e/dx/(N kappa)"
    return frame


def curves(dist, x=None, points=2001):
    """The ELS curves F, E_e, E_d, energy rate and broken fraction as a DataFrame: at the strains `x`
    (an array; continuous distributions), else at `points` equally spaced strains up to the end of
    the distribution's support."""
    if x is not None:
        return _frame(_rupture.fbm_theory_at(dist, np.asarray(x, dtype=float)))
    return _frame(_rupture.fbm_curve(dist, int(points)))


def simulate(dist, fibers, seed=1, control="strain", sharing="els", points=2001):
    """A finite bundle of `fibers` thresholds drawn with `seed` (the same bundle on every platform),
    loaded under "strain" or "load" control with "els" or (load control only) "lls" sharing.
    Returns (curve DataFrame, dict of the measured maxima; under load control also "bursts"
    {size: count} and "final_burst")."""
    out = _rupture.fbm_simulate(dist, int(fibers), int(seed), control, sharing, int(points))
    measured = out["measured"]
    for key in ("bursts", "final_burst"):
        if key in out:
            measured[key] = out[key]
    return _frame(out["curve"]), measured
