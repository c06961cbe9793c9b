#!/usr/bin/env python3
"""How far δ_x moves with where a run's rows fall (docs/analysis.md, "Where the rows fall").

Usage: dem_row_phases.py RUPTURE RUN_DIR [RUN_DIR ...]

Each RUN_DIR holds a curves.csv written by `rupture run` (bench/dem_delta_spread.sh writes seven).
The curve's rows are split into k interleaved phases (every k-th row, starting at row 0 .. k-1; the
comment lines kept), for k = 2 and 4, and each phase is analysed with default options, as is the
whole curve. Printed per run: the whole curve's δ_x and its reported sd, then each thinning's δ_x per
phase ("rejected" where the analysis rejects the phase, "-" where it finds no δ_x), their sd over the
accepted phases and the mean of the sds those report. The thinned curves are what the same run would have written with rows
k times as far apart, at k different starting steps: the same physics, other samples of it.
Standard library only.
"""
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile

from curve_table import read_table


def analyse(rupture, curve, out):
    done = subprocess.run([rupture, "analyze", str(curve), "-o", str(out)], capture_output=True, text=True)
    if not out.exists():
        return None
    result = json.loads(out.read_text())
    out.unlink()
    if done.returncode != 0 and not result.get("delta_x"):
        return None
    delta = result.get("delta_x") or {}
    if "value" not in delta:
        return None
    return {"delta_x": delta["value"], "sd": delta.get("sd", float("nan")), "accepted": result.get("accepted")}


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    rupture = argv[1]
    print("| run | rows | δ_x [%] (sd) | every 2nd row: δ_x per phase [%] | sd over phases | mean reported sd "
          "| every 4th row: δ_x per phase [%] | sd over phases | mean reported sd |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for run in argv[2:]:
            run = pathlib.Path(run)
            table = read_table(run / "curves.csv")
            header = ",".join(table.names)
            rows = [",".join(repr(v) for v in row) for row in table.rows]
            whole = analyse(rupture, run / "curves.csv", tmp / "whole.json")
            cells = [run.name, str(len(rows)),
                     "%.4f (%.4f)" % (whole["delta_x"], whole["sd"]) if whole else "-"]
            for k in (2, 4):
                phases = []
                for phase in range(k):
                    curve = tmp / ("phase%d.csv" % phase)
                    curve.write_text("\n".join(table.comments + [header] + rows[phase::k]) + "\n")
                    phases.append(analyse(rupture, curve, tmp / "phase.json"))
                found = [p for p in phases if p and p["accepted"]]
                cells.append(", ".join(("%.4f" % p["delta_x"]) + ("" if p["accepted"] else " rejected") if p else "-"
                                       for p in phases))
                cells.append("%.4f" % statistics.stdev(p["delta_x"] for p in found) if len(found) > 1 else "-")
                cells.append("%.4f" % statistics.fmean(p["sd"] for p in found) if found else "-")
            print("| " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
