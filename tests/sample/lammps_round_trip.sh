#!/usr/bin/env bash
# Reads a rupture sample into LAMMPS itself (atom style hybrid sphere bond), lets LAMMPS write it
# back with write_data, reads that into rupture and checks that particles, bonds and glued layers
# are identical. usage: lammps_round_trip.sh RUPTURE LMP WORK_DIR
set -euo pipefail
rupture=$1 lmp=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export CI=1
"$rupture" sample generate --preset tissue-small --seed 8 --out original.sample >/dev/null
"$rupture" sample convert original.sample original.data >/dev/null
cat >in.read <<'LAMMPS'
units       si
atom_style  hybrid sphere bond
boundary    f f f
read_data   original.data
group       bottom type 2
group       top type 3
write_data  lammps.data
LAMMPS
"$lmp" -in in.read -log none -echo none -screen lammps.out
"$rupture" sample convert lammps.data back.sample >/dev/null
# Same numbers, same order: only the provenance comments may differ.
if ! diff <(grep -v '^#' original.sample) <(grep -v '^#' back.sample) >diff.txt; then
  echo "LAMMPS round trip changed the sample:"; head -20 diff.txt; exit 1
fi
# LAMMPS's own count of the glued groups must match rupture's.
bottom=$("$rupture" sample info --json original.sample | python3 -c 'import json,sys; print(json.load(sys.stdin)["glued_layers"]["bottom"])')
grep -q "^$bottom atoms in group bottom" lammps.out || { echo "LAMMPS group bottom differs from $bottom"; grep "in group" lammps.out; exit 1; }
echo "LAMMPS read and wrote back the sample unchanged ($bottom particles glued to the bottom plate)"
