"""Reads rupture's .vtp files with VTK itself (Debian python3-vtk9), as ParaView would.

usage: read_vtp_with_vtk.py RUPTURE_BINARY WORK_DIR [EXAMPLES_DIR]
Generates the reduced tissue, converts it to .vtp, reads it with vtkXMLPolyDataReader and checks the
counts and arrays against `rupture sample info --json`; with EXAMPLES_DIR, also a run's snapshot
(binary, zlib-compressed) with its vector arrays. Exits non-zero on any mismatch or VTK error.
"""
import json
import os
import subprocess
import sys

import vtk


def read(picture, errors):
    reader = vtk.vtkXMLPolyDataReader()
    reader.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
    reader.SetFileName(picture)
    reader.Update()
    if reader.GetErrorCode() != 0:
        errors.append("error code")
    return reader.GetOutput()


def snapshot_checks(rupture, work, examples, env, errors):
    """A run's snapshot: points, bonds and the vector arrays a ParaView user colours by."""
    run = os.path.join(work, "run")
    subprocess.run([rupture, "run", os.path.join(examples, "block.toml"), "--set", "output.snapshot_interval=500",
                    "--set", "stop.max_steps=1000", "--overwrite", "-o", run], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    data = read(os.path.join(run, "snapshots", "step_0000000500.vtp"), errors)
    record = json.load(open(os.path.join(run, "run.json")))
    checks = {"snapshot points = particles": data.GetNumberOfPoints() == record["sample"]["particles"],
              "snapshot lines = intact bonds": data.GetNumberOfLines() > 0}
    for name in ("displacement_mm", "velocity_mm_per_s", "force_N"):
        array = data.GetPointData().GetArray(name)
        checks[name + " with 3 components"] = array is not None and array.GetNumberOfComponents() == 3
    moved = data.GetPointData().GetArray("displacement_mm")
    checks["the top moved up"] = moved is not None and moved.GetRange(1)[1] > 0
    return checks


def main():
    rupture, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    sample, picture = os.path.join(work, "t.sample"), os.path.join(work, "t.vtp")
    env = dict(os.environ, CI="1")
    subprocess.run([rupture, "sample", "generate", "--preset", "tissue-small", "--seed", "4", "--out", sample],
                   check=True, env=env, stdout=subprocess.DEVNULL)
    subprocess.run([rupture, "sample", "convert", sample, picture], check=True, env=env, stdout=subprocess.DEVNULL)
    info = json.loads(subprocess.run([rupture, "sample", "info", "--json", sample], check=True, env=env,
                                     capture_output=True, text=True).stdout)

    errors = []
    observer = vtk.vtkFileOutputWindow()  # keep VTK quiet; errors are caught below
    vtk.vtkOutputWindow.SetInstance(observer)
    data = read(picture, errors)
    checks = {
        "points = particles": data.GetNumberOfPoints() == info["particles"],
        "lines = bonds": data.GetNumberOfLines() == info["bonds"],
        "radius array": data.GetPointData().GetArray("radius") is not None,
        "group array": data.GetPointData().GetArray("group") is not None,
        "rest_length array": data.GetCellData().GetArray("rest_length") is not None,
    }
    if checks["radius array"]:
        low, high = data.GetPointData().GetArray("radius").GetRange()
        checks["radii in [r_min, r_max]"] = abs(low - info["radius"]["min"]["value"]) < 1e-12 and abs(high - info["radius"]["max"]["value"]) < 1e-12
    if len(sys.argv) > 3:
        checks.update(snapshot_checks(rupture, work, sys.argv[3], env, errors))
    checks["no reader errors"] = not errors
    failed = [name for name, ok in checks.items() if not ok]
    print("VTK", vtk.vtkVersion.GetVTKVersion(), "read", picture, ":", "ok" if not failed else "FAILED " + ", ".join(failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
