"""The precursor analysis of a loading curve (`rupture analyze`): x_p (energy-rate maximum), x_c
(force maximum), x_m, the delay delta_x = x_c - x_p with its sampling distribution, Gamma, A_r, the
FBM comparison, acceptance and the breaking mechanism.
"""
from collections import namedtuple
from pathlib import Path

import numpy as np

from . import _rupture

Measured = namedtuple("Measured", "value error unit")
Measured.__doc__ = "A measured number with its one-sigma uncertainty (0 when not estimated) and unit."


def _number(value):
    """A JSON number, or NaN where the file has null (a value JSON cannot hold)."""
    return float("nan") if value is None else value


class Analysis:
    """One analysis. `document` is the whole analysis.json as a dict; the attributes below are read from
    it. Quantities the analysis did not find are None."""

    _MEASURED = ("x_p", "x_c", "x_m", "F_c", "E_max", "Erate_max", "Gamma", "A_r", "delta_x_direct")

    def __init__(self, document):
        curves = document.get("curves") or {}
        if not isinstance(curves.get("filtered_force", {}), dict):
            raise _rupture.InputError(f"analysis.json of an earlier build ({document.get('version', '?')}): its "
                                      "numbers are not {value, unit} objects; rerun rupture analyze")
        self.document = document
        for key in self._MEASURED:
            m = document.get(key)
            setattr(self, key, None if m is None else
                    Measured(_number(m["value"]), _number(m.get("error", 0.0)), m.get("unit", "")))
        # x_c's and x_p's intervals, where the bootstrap ran (docs/analysis.md: their factors).
        for key in ("x_c", "x_p"):
            m = document.get(key) or {}
            for level in ("ci68", "ci95"):
                setattr(self, f"{key}_{level}", tuple(m[level]) if level in m else None)
        # Whether each quantity's intervals are calibrated (their factors passed a held-out check) or
        # not (the bootstrap's own, or factors that failed their check), with no coverage promise;
        # False where the file does not say.
        self.intervals_calibrated = {
            key: bool(((document.get(key) or {}).get("interval_scales") or {}).get("calibrated", False))
            for key in ("x_c", "x_p", "delta_x")}
        delta = document.get("delta_x")
        self.delta_x = None if delta is None else Measured(_number(delta["mean"]), _number(delta["sd"]), delta["unit"])
        self.delta_x_ci95 = None if delta is None else tuple(delta["ci95"])
        self.delta_x_ci68 = None if delta is None else tuple(delta["ci68"])
        self.accepted = bool(document.get("accepted"))
        self.rejection = document.get("rejection") or None
        mechanism = document.get("mechanism") or {}
        self.mechanism = mechanism.get("class")
        alpha = document.get("alpha") or {}
        self.alpha = alpha.get("from_delta_over_x_p")
        self.units = {name: curves[key]["unit"] for name, key in
                      (("strain", "x0"), ("force", "filtered_force"), ("energy", "filtered_elastic_energy"))
                      if key in curves}

    @property
    def posterior(self):
        """delta_x's sampling distribution as (delta, density) numpy arrays, in the strain unit."""
        dist = (self.document.get("delta_x") or {}).get("sampling_distribution")
        if dist is None:
            return None
        return (np.asarray(dist["delta"]["value"], dtype=float),
                np.asarray(dist["density"]["value"], dtype=float))

    def __repr__(self):
        def show(m):
            return "None" if m is None else f"{m.value:.4g} ± {m.error:.2g} {m.unit}"
        return (f"Analysis(x_p={show(self.x_p)}, x_c={show(self.x_c)}, delta_x={show(self.delta_x)}, "
                f"accepted={self.accepted}, mechanism={self.mechanism!r})")


def analyze(data, force=None, energy=None, *, units=("%", "N", "mJ"), delay_method="fitted-maxima",
            replicates=0, seed=1, walk_profile=True, force_peak_form="smooth", smoothing_floor=0.0, rows=None):
    """Analyses a curve given as
      - a DataFrame with columns strain, force (or force_top) and elastic_energy, units taken from
        names like strain[%] (e.g. Run.curves, read_curves()); a run's strain_mean, force_top_mean and
        elastic_energy_mean (means over each row's interval) where it has all three,
      - the path of a curves CSV (its breaks.csv beside it, if any, is read as the CLI does), or
      - three arrays: analyze(strain, force, energy, units=("%", "N", "mJ")).
    delay_method: "fitted-maxima" (default) or "shift-l1" (the paper's inversion, for comparison);
    replicates: bootstrap noise replicates (0: the default 200); seed: their seed;
    walk_profile: on curves read as a random walk, the walk's steps follow the curve's falling
    stiffness (default, as rupture analyze); False: one stationary step (rupture analyze
    --no-walk-profile);
    force_peak_form: "smooth" (default) or "corner": a force that turns at its peak and sags to a
    collapse, as a DEM tissue's does, has x_c at the corner of two lines on the rows there (rupture
    analyze --force-peak-form corner);
    smoothing_floor: where the noise of F or E_e reads as white, the automatic filter averages over at
    least this share of the rows up to the force peak, where they are 100 or more (default 0: the noise
    alone chooses; 0.25 mends DEM runs at rows every 100-200 steps; rupture analyze --smoothing-floor);
    rows: what a row holds, "instants" or "interval-means" (each row the mean over its interval, as a
    run's *_mean columns hold; the noise model reads a walk on such rows by its own term); None
    (default): interval-means where a run's *_mean columns are read, else instants (rupture analyze
    --rows)."""
    options = dict(delay_method=str(delay_method), replicates=int(replicates), seed=int(seed),
                   walk_profile=bool(walk_profile), force_peak_form=str(force_peak_form),
                   smoothing_floor=float(smoothing_floor), rows=None if rows is None else str(rows))
    if isinstance(data, (str, Path)):
        return Analysis(_rupture.analyze_file(str(data), **options))
    if force is None and hasattr(data, "columns"):
        frame = data
        names = [str(c) for c in frame.columns]
        try:
            *picked, rows_read = _rupture.columns_read(names)  # as rupture analyze picks them
            columns = [names[i] for i in picked]
        except _rupture.InputError as e:  # its fix names the command line's options; say Python's
            raise _rupture.InputError(f"{e}; from Python: name the DataFrame's columns strain, force (or "
                                      "force_top) and elastic_energy, or pass three arrays") from None
        found = frame.attrs.get("units", {})
        units = tuple(found.get(c, "1") for c in columns)
        strain, force, energy = (frame[c].to_numpy(dtype=float) for c in columns)
        options["rows"] = options["rows"] or rows_read
    else:
        strain = data
        if force is None or energy is None:
            raise _rupture.InputError("analyze: give a DataFrame, a CSV path, or three arrays (strain, force, energy)")
    return Analysis(_rupture.analyze_arrays(np.asarray(strain, dtype=float).tolist(),
                                            np.asarray(force, dtype=float).tolist(),
                                            np.asarray(energy, dtype=float).tolist(),
                                            units[0], units[1], units[2], **options))
