#!/usr/bin/env python3
"""How the points of a scan top out, and x_c's error there with either form of the force's peak
(docs/analysis.md, "The study scan's points: two ways to top out").

Usage: PYTHONPATH=build/release/python dem_scan_tops.py RUPTURE SCAN_CONFIG OUT POINT:BASE [POINT:BASE ...]

Each POINT (its index in the scan) is run as the scan runs it (`rupture scan SCAN_CONFIG --task-index
POINT -o OUT/scan`), then again from the exact config that run wrote (its run.json), through the
Python package's rupture.run, with a curve row every BASE steps (OUT/dense-POINT). BASE must divide the point's own row interval and 200 and 400
steps. From the dense run: the top's shape (bench/dem_top_shape.py, running means over 400 steps, the
force's top sought within 0.7-1.3 times the scan's own x_c), then the scan's row spacing rebuilt at
several starts as samples and as means and analysed with the default form of the force's peak and
with `--force-peak-form corner` (bench/dem_row_means.py), scored against the dense reference x_c
(bench/dem_x_c_reference.py, running means over 200 and 400 steps), beside where the scan's own
analysis found the collapse's onset. Tables go to standard output,
the per-analysis tables to OUT/x_c-smooth.csv and OUT/x_c-corner.csv. Needs the rupture package.
"""
import json
import pathlib
import subprocess
import sys

try:
    import rupture as rupture_package
except ImportError:
    sys.exit("dem_scan_tops.py: the rupture Python package is not importable; put the build's python folder "
             "on PYTHONPATH (e.g. PYTHONPATH=build/release/python)")

BENCH = pathlib.Path(__file__).resolve().parent


def run(command, log):
    with open(log, "w", encoding="utf-8") as f:
        if subprocess.run([str(c) for c in command], stdout=f, stderr=subprocess.STDOUT).returncode != 0:
            sys.exit(f"{' '.join(map(str, command))} failed; see {log}")


def script(name, *args):
    done = subprocess.run([sys.executable, str(BENCH / name), *map(str, args)], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{name}: {done.stderr.strip() or done.stdout.strip()}")
    return done.stdout


def main(argv):
    if len(argv) < 5:
        sys.exit(__doc__)
    rupture, scan_config, out = argv[1], argv[2], pathlib.Path(argv[3])
    try:
        points = [tuple(int(v) for v in spec.split(":")) for spec in argv[4:]]
    except ValueError:
        sys.exit("give each point as POINT:BASE, e.g. 24:2")
    out.mkdir(parents=True, exist_ok=True)
    shapes, errors = [], []
    for point, base in points:
        run([rupture, "scan", scan_config, "--task-index", point, "-o", out / "scan", "--jobs", "1"],
            out / f"scan-{point}.log")
        plan = json.loads((out / "scan" / "plan.json").read_text(encoding="utf-8"))
        entry = next(p for p in plan["points"] if p["index"] == point)
        spacing = entry["output_interval"]
        if spacing % base or 200 % base:
            sys.exit(f"point {point}: BASE {base} must divide its row interval {spacing} and 200 steps")
        attempts = (out / "scan" / entry["folder"]).glob("attempt-*")
        attempt = max(attempts, key=lambda folder: int(folder.name.split("-")[1]))
        analysis = json.loads((attempt / "analysis.json").read_text(encoding="utf-8"))
        x_c = analysis["x_c"]["value"]
        onset = (analysis.get("collapse_onset") or {}).get("value")
        dense = out / f"dense-{point}"
        # The run's exact config, as run.json holds it, with rows every BASE steps.
        config = json.loads((attempt / "run.json").read_text(encoding="utf-8"))["config"]
        rupture_package.run(config, out=dense, set=[f"output.interval={base}", "run.threads=2", "monitor.enabled=false"],
                            overwrite=True)
        curves = dense / "curves.csv"
        top_range = f"{0.7 * x_c},{1.3 * x_c}"
        shapes.append((entry, script("dem_top_shape.py", "--top-range", top_range, "--width", 400 // base,
                                     curves).splitlines()))
        for form, options in (("smooth", []), ("corner", ["--force-peak-form", "corner"])):
            table = out / f"x_c-{form}.csv"
            script("dem_row_means.py", rupture, curves, base, spacing, table, *options)
            reference = script("dem_x_c_reference.py", "--top-range", top_range, "--widths",
                               f"{200 // base},{400 // base}", table, curves).splitlines()
            errors.append((entry, form, reference, onset))
    print("\n".join(shapes[0][1][:2]).replace("| run |", "| point (k_n, b_d) |", 1))
    for entry, lines in shapes:
        name = f"{entry['index']} ({entry['k_n']['value']:g}, {entry['b_d']['value']:g})"
        print(lines[-1].replace(lines[-1].split("|")[1], f" {name} ", 1))
    print("\n| point | reference x_c [%] | collapse onset / reference | form " + errors[0][2][1])
    print("|---|---|---|---" + errors[0][2][2])
    for entry, form, lines, onset in errors:
        reference = lines[0].split("reference x_c ")[1].split()[0]
        gap = f"{onset / float(reference):.3f}" if onset else "none"
        for row in lines[3:]:
            print(f"| {entry['index']} | {reference} | {gap} | {form} " + row)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
