#!/usr/bin/env bash
# A sample made by LAMMPS itself, not by rupture (tests/sample/lammps_slab.in: a bonded simple-cubic
# slab of 165 spheres in a box with a margin, written by write_data), loaded with its glued layers
# and pulled apart by `rupture run`. usage: lammps_slab.sh RUPTURE LMP WORK_DIR SOURCE_DIR
set -euo pipefail
rupture=$1 lmp=$2 work=$3 source=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export CI=1
"$lmp" -in "$source/lammps_slab.in" -log none -echo none -screen lammps.out
"$rupture" sample info --json slab.data >info.json
python3 - <<'PY'
import json
info = json.load(open("info.json"))
assert info["particles"] == 165 and info["bonds"] == 392, info
# 5 x 3 spheres in the bottom and the top layer of the 5 x 11 x 3 slab, found against the particles
# (the file's box reaches 1.5 mm above them).
assert info["glued_layers"] == {"bottom": 15, "top": 15}, info["glued_layers"]
PY
cat >slab.toml <<'TOML'
[sample]
file = "slab.data"
[bonds]
stiffness = 1e3
break_distance = 0.002
[loading]
speed = 500.0
ramp_steps = 500
[stop]
extra_strain = 0.5
max_strain = 20.0
[output]
interval = 50
TOML
"$rupture" run slab.toml -o run >run.out
python3 - <<'PY'
import json
run = json.load(open("run/run.json"))
assert run["status"] == "finished" and run["stop_reason"] == "separated", (run["status"], run["stop_reason"])
assert run["broken_bonds"] > 0
assert run["energy_balance"]["max_error_relative_to_work"] < 1e-2, run["energy_balance"]
print(f"LAMMPS's slab: separated at {run['separation_strain']['value']:.3g} %, {run['broken_bonds']} bonds broken")
PY
