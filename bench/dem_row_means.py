#!/usr/bin/env python3
"""Single samples against means over the row's interval, on one DEM run (docs/analysis.md, "Where the
rows fall").

Usage: dem_row_means.py RUPTURE DENSE_CURVES [BASE_STEPS=10] [SPACINGS=100,200,400] [TABLE.csv] [ANALYZE_OPTION...]

DENSE_CURVES is a curves.csv written with a row every BASE_STEPS steps (`rupture run CONFIG --set
output.interval=10`). From it, for rows every SPACINGS steps, five curves are built that start at five
different steps (offsets spread over one spacing): once keeping each spacing's single rows ("sample",
what a run writes with that output.interval as a snapshot) and once averaging the dense rows over each
spacing ("mean", what rupture run writes in its *_mean columns, and written under those names so that
the analysis reads them as means). Each is analysed with default options. Printed per spacing and kind:
δ_x (sd) for each start ("rejected" where the analysis rejects the curve, "-" where it finds no δ_x) and
their sd over the accepted starts. With TABLE.csv, every analysis is also appended to that file as a
row (the dense file, spacing, kind, starting step, accepted, δ_x and its sd, x_p, x_c and their sds in
the run's strain unit, the rejection), the header written where the file is new: docs/analysis.md's
"The bootstrap's noise read on the loading" takes the median sd and the rms over runs of δ_x's sd
over the starts from such a table of five runs.
The dense file's own *_mean columns are dropped first, so that both kinds are built from the single
samples. Any further arguments go to every `rupture analyze` (e.g. `--force-peak-form corner`; they need a TABLE before them). Standard library
only.
"""
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

from curve_table import read_table


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    rupture, dense = argv[1], pathlib.Path(argv[2])
    base = int(argv[3]) if len(argv) > 3 else 10
    spacings = [int(v) for v in argv[4].split(",")] if len(argv) > 4 else [100, 200, 400]
    table = pathlib.Path(argv[5]) if len(argv) > 5 else None
    analyze_options = argv[6:]
    if table and not table.exists():
        table.write_text("dense,spacing,kind,start,accepted,delta_x,delta_x_sd,x_p,x_p_sd,x_c,x_c_sd,rejection\n")
    dense_table = read_table(dense)
    keep = [i for i, name in enumerate(dense_table.names) if "_mean[" not in name]
    header = ",".join(dense_table.names[i] for i in keep)
    rows = [[row[i] for i in keep] for row in dense_table.rows]
    with tempfile.TemporaryDirectory() as tmp:
        curve, out = pathlib.Path(tmp) / "curve.csv", pathlib.Path(tmp) / "analysis.json"

        # The means go under the names a run gives them, so that the analysis reads them as means.
        means_header = ",".join(name.replace("[", "_mean[", 1) if name.split("[")[0] in
                                ("strain", "force_top", "elastic_energy") else name
                                for name in header.split(","))

        def analyse(built, kind):
            curve.write_text("\n".join([means_header if kind == "mean" else header] +
                                       [",".join(repr(v) for v in row) for row in built]) + "\n")
            subprocess.run([rupture, "analyze", str(curve), "-o", str(out), *analyze_options], capture_output=True)
            result = json.loads(out.read_text()) if out.exists() else {}
            delta = result.get("delta_x") or {}
            return (delta["value"], delta["sd"], bool(result.get("accepted"))) if "value" in delta else None, result

        def record(result, spacing, kind, start):
            if not table:
                return
            value = lambda name, field: str((result.get(name) or {}).get(field, ""))
            rejection = (result.get("rejection") or "").replace('"', "'")
            with table.open("a") as f:
                f.write(",".join([str(dense), str(spacing), kind, str(start), str(int(bool(result.get("accepted")))),
                                  value("delta_x", "value"), value("delta_x", "sd"), value("x_p", "value"),
                                  value("x_p", "error"), value("x_c", "value"), value("x_c", "error"),
                                  f'"{rejection}"']) + "\n")

        print("| rows every (steps) | kind | δ_x (sd) [%] at five starts | sd over the starts [%] |")
        print("|---|---|---|---|")
        for spacing in spacings:
            k = spacing // base
            for kind in ("sample", "mean"):
                found = []
                for start in range(0, k, max(1, k // 5)):
                    if kind == "sample":
                        built = [rows[0]] + rows[1 + start::k]
                    else:
                        built = [rows[0]] + [[sum(c) / k for c in zip(*rows[i:i + k])]
                                             for i in range(1 + start, len(rows) - k + 1, k)]
                    delta, result = analyse(built, kind)
                    found.append(delta)
                    record(result, spacing, kind, start)
                values = [f[0] for f in found if f and f[2]]
                cells = ", ".join(("%.4f (%.4f)" % f[:2]) + ("" if f[2] else " rejected") if f else "-"
                                  for f in found)
                spread = "%.4f" % statistics.stdev(values) if len(values) > 1 else "-"
                print(f"| {spacing} | {kind} | {cells} | {spread} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
