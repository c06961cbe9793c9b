"""A sample made by GenGeo (Debian python3-gengeo), the paper's own generator, read by rupture.

usage: gengeo_sample.py RUPTURE_BINARY WORK_DIR [WIDTH HEIGHT DEPTH]
Packs a box with GenGeo's InsertGenerator3D (radii 0.2-0.6 mm), bonds touching pairs, writes the
LSMGeometry file, and checks that `rupture sample info --json` sees the same particles, bonds and
solid volume, and that a round trip through LSMGeometry keeps every number.
"""
import json
import os
import subprocess
import sys
import time

import gengeo as gg


def main():
    rupture, work = sys.argv[1], sys.argv[2]
    size = [float(v) for v in sys.argv[3:6]] if len(sys.argv) >= 6 else [10.0, 6.0, 5.0]
    os.makedirs(work, exist_ok=True)
    geo = os.path.join(work, "gengeo.geo")
    low, high = gg.Vector3(0.0, 0.0, 0.0), gg.Vector3(*size)
    box = gg.BoxWithPlanes3D(low, high)
    box.addPlane(gg.Plane(low, gg.Vector3(1.0, 0.0, 0.0)))
    box.addPlane(gg.Plane(low, gg.Vector3(0.0, 1.0, 0.0)))
    box.addPlane(gg.Plane(low, gg.Vector3(0.0, 0.0, 1.0)))
    box.addPlane(gg.Plane(high, gg.Vector3(-1.0, 0.0, 0.0)))
    box.addPlane(gg.Plane(high, gg.Vector3(0.0, -1.0, 0.0)))
    box.addPlane(gg.Plane(high, gg.Vector3(0.0, 0.0, -1.0)))
    table = gg.MNTable3D(low, high, 2.5 * 0.6, 1)
    start = time.process_time()
    packer = gg.InsertGenerator3D(0.2, 0.6, 1000, 1000, 1.0e-6, True)
    packer.generatePacking(box, table, 0, 0)
    table.generateBonds(0, 1.0e-5, 0)
    seconds = time.process_time() - start
    table.write(geo, 1)
    solid = table.getSumVolume(0)

    env = dict(os.environ, CI="1")
    info = json.loads(subprocess.run([rupture, "sample", "info", "--json", geo], check=True, env=env,
                                     capture_output=True, text=True).stdout)
    with open(geo) as f:
        lines = f.read().splitlines()
    particles = int(lines[lines.index("Simple") + 1])
    bonds = int(lines[lines.index("BeginConnect") + 1])
    volume = size[0] * size[1] * size[2]
    print(f"GenGeo packed {particles} particles, {bonds} bonds, solid fraction {solid / volume:.4f} "
          f"in {seconds:.1f} s CPU; rupture reads {info['particles']} particles, {info['bonds']} bonds, "
          f"solid fraction {info['solid_fraction']:.4f}, coordination {info['mean_coordination']:.2f}, "
          f"largest overlap {info['max_overlap']:.2g} mm")
    ok = (info["particles"] == particles and info["bonds"] == bonds and particles > 100
          and abs(info["solid_fraction"] - solid / volume) < 1e-6 * solid / volume)

    # Round trip rupture -> LSMGeometry -> rupture: the same particles and bonds, number for number.
    own, back, again = (os.path.join(work, name) for name in ("gengeo.sample", "back.geo", "again.sample"))
    for source, target in ((geo, own), (own, back), (back, again)):
        subprocess.run([rupture, "sample", "convert", source, target], check=True, env=env, stdout=subprocess.DEVNULL)
    def content(path):
        with open(path) as f:
            return [line for line in f if not line.startswith("#")]
    ok = ok and content(own) == content(again)
    print("ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
