"""Reading what rupture writes: curves.csv, breaks.csv and run.json of a run folder, results.csv and
scan.json of a scan folder, as pandas DataFrames and dicts.

rupture's tables start with '#' lines (version, command, conventions) and name each column's unit in
brackets, e.g. strain[%]. The DataFrames keep those names and give the units again in
`frame.attrs["units"]` ({column: unit}; text columns have none) and the '#' lines in
`frame.attrs["comments"]`.
"""
import json
import re
from pathlib import Path

import pandas as pd

_UNIT = re.compile(r"^(?P<name>.*)\[(?P<unit>[^\]]*)\]$")


def read_curves(path):
    """Any rupture CSV table (curves.csv, breaks.csv, results.csv, an FBM curve) as a DataFrame."""
    path = Path(path)
    comments = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if not line.startswith("#"):
                break
            comments.append(line[1:].strip())
    frame = pd.read_csv(path, skiprows=len(comments))
    frame.attrs["units"] = {c: m.group("unit") for c in frame.columns if (m := _UNIT.match(c))}
    frame.attrs["comments"] = comments
    frame.attrs["source"] = str(path)
    return frame


def _json(path):
    path = Path(path)
    return json.loads(path.read_text(encoding="utf-8")) if path.exists() else None


class Run:
    """A run folder: `curves` and `breaks` (DataFrames), `record` (run.json: status, config, sample,
    energy balance, monitor), `analysis` (analysis.json, None before `rupture analyze`) and `folder`."""

    def __init__(self, folder):
        self.folder = Path(folder)
        if not (self.folder / "curves.csv").exists():
            from ._rupture import InputError
            raise InputError(f"{self.folder}: no curves.csv; give a folder written by rupture run")
        self.curves = read_curves(self.folder / "curves.csv")
        self.breaks = read_curves(self.folder / "breaks.csv") if (self.folder / "breaks.csv").exists() else None
        self.record = _json(self.folder / "run.json")
        self.analysis = _json(self.folder / "analysis.json")

    @property
    def status(self):
        return None if self.record is None else self.record.get("status")

    def __repr__(self):
        return f"Run({str(self.folder)!r}, status={self.status!r}, rows={len(self.curves)})"


def read_run(folder):
    """A run folder (`rupture run`, `rupture.run`, a scan point's attempt folder) as a Run."""
    return Run(folder)


def read_scan(folder):
    """A scan folder's results.csv as a DataFrame, one row per point (units in attrs, scan.json in
    attrs["scan"])."""
    folder = Path(folder)
    if not (folder / "results.csv").exists():
        from ._rupture import InputError
        raise InputError(f"{folder}: no results.csv; give a folder written by rupture scan")
    frame = read_curves(folder / "results.csv")
    frame.attrs["scan"] = _json(folder / "scan.json")
    return frame
