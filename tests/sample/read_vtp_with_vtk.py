"""Reads a sample's .vtp with VTK itself (Debian python3-vtk9), as ParaView would.

usage: read_vtp_with_vtk.py RUPTURE_BINARY WORK_DIR
Generates the reduced tissue, converts it to .vtp, reads it with vtkXMLPolyDataReader and checks the
counts and arrays against `rupture sample info --json`. Exits non-zero on any mismatch or VTK error.
"""
import json
import os
import subprocess
import sys

import vtk


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
    reader = vtk.vtkXMLPolyDataReader()
    reader.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
    reader.SetFileName(picture)
    reader.Update()
    data = reader.GetOutput()
    checks = {
        "no reader errors": not errors and reader.GetErrorCode() == 0,
        "points = particles": data.GetNumberOfPoints() == info["particles"],
        "lines = bonds": data.GetNumberOfLines() == info["bonds"],
        "radius array": data.GetPointData().GetArray("radius") is not None,
        "group array": data.GetPointData().GetArray("group") is not None,
        "rest_length array": data.GetCellData().GetArray("rest_length") is not None,
    }
    if checks["radius array"]:
        low, high = data.GetPointData().GetArray("radius").GetRange()
        checks["radii in [r_min, r_max]"] = abs(low - info["radius"]["min"]) < 1e-12 and abs(high - info["radius"]["max"]) < 1e-12
    failed = [name for name, ok in checks.items() if not ok]
    print("VTK", vtk.vtkVersion.GetVTKVersion(), "read", picture, ":", "ok" if not failed else "FAILED " + ", ".join(failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
