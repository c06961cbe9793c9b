#!/usr/bin/env bash
# Times rupture and LAMMPS on the same model and sample, on this machine, and checks first that the
# LAMMPS deck is the same model. Needs `lmp` (Debian: `scripts/bootstrap --interop`, or apt-get
# install lammps) and OpenMPI's mpirun.
#
#   bench/compare/lammps/run.sh [--check] [RUPTURE]   # RUPTURE defaults to build/release/bin/rupture
#
# --check runs step 1 only and fails where the two codes' forces differ by more than 1e-9 (a test
# where `lmp` is installed).
#
# 1. Same model: the fast pull (bench/runs/fast-pull.toml) up to just before its first bond breaks
#    (1,200 steps), contacts off in both codes; the plate force of every 100th step is compared.
# 2. Speed: the same sample pulled at 50 mm/s for STEPS steps (20,000 by default: the bonds all hold),
#    contacts on: `rupture bench --run` on 1 and 2 threads against `lmp` on 1 and 2 MPI ranks (the
#    loop time LAMMPS prints). LAMMPS's granular pair style also pushes bonded pairs apart where they
#    are compressed (this release does not exclude bonded pairs from it), so its curve runs ~2 %
#    stiffer here: the work per step is comparable, the physics not exactly.
# PRESET=tissue runs both parts on the standard tissue (26,025 particles) instead of the reduced one.
# Breaking is not timed: `fix bond/break` takes one bond type, and so one rest length, per fix;
# see docs/performance.md for what binning the rest lengths costs.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
check_only=0
if [ "${1:-}" = "--check" ]; then check_only=1; shift; fi
rupture=$(realpath "${1:-$root/build/release/bin/rupture}")
steps=${STEPS:-20000}
preset=${PRESET:-tissue-small}
command -v lmp > /dev/null || { echo "run.sh: no lmp on PATH; install Debian's lammps (scripts/bootstrap --interop)" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
config="$root/bench/runs/fast-pull.toml"
"$rupture" sample generate --preset "$preset" --seed 1 --out sample.rsample > /dev/null
"$rupture" sample convert sample.rsample sample.data > /dev/null
"$rupture" check "$config" --set sample.preset="$preset" | sed -n '/^{/,/^}/p' > config.json  # the resolved configuration

# 1. Same model.
"$rupture" run "$config" --set sample.preset="$preset" --set stop.max_steps=1200 --set contacts.stiffness_factor=0 --set run.threads=1 \
  --set output.folder="$work/rupture-check" > /dev/null
# The run's own dt, plate separation, bond stiffness and break distance (run.json), and the contact
# stiffness the config gives (k_c = stiffness_factor k_n) for step 2.
read -r dt l0 k b kc < <(python3 -c "
import json
j = json.load(open('rupture-check/run.json'))
p, c = j['plan'], j['config']
if c['bonds']['break_rule'] != 'absolute' or c['bonds']['scale_stiffness'] or c['glue']['mode'] != 'rigid':
    raise SystemExit('$config: the deck models absolute-rule bonds of one stiffness and rigid glue only')
k = c['bonds']['stiffness']
print(repr(p['dt']['value']), repr(p['plate_separation']['value']), repr(k), repr(c['bonds']['break_distance']),
      repr(k * json.load(open('config.json'))['contacts']['stiffness_factor']))")
python3 "$here/bin_bonds.py" sample.data exact.data exact-coeffs.in --types 0 --stiffness "$k" --break-distance "$b" > /dev/null
deck=(-in "$here/pull.in" -var data exact.data -var coeffs exact-coeffs.in -var dt "$dt" -var ramp 2000
      -var l0 "$l0" -var skin 0.05 -var interval 100 -log none)
lmp "${deck[@]}" -var breaking /dev/null -var steps 1200 -var speed 5000 -var kc 0 -var curve lammps-check.txt > /dev/null
python3 - <<'PY'
rows = [l.split(",") for l in open("rupture-check/curves.csv") if not l.startswith("#")]
head = rows[0]
step, force = head.index("step[1]"), head.index("force_top[N]")
ours = {int(r[step]): float(r[force]) for r in rows[1:]}
theirs = [float(l.split()[1]) for l in open("lammps-check.txt").read().splitlines()[1:]]
worst = max(abs(f - ours[100 * i]) / abs(ours[100 * i]) for i, f in enumerate(theirs) if i > 0)
print(f"same model: plate force of LAMMPS against rupture over 1,200 steps (contacts off): "
      f"largest relative difference {worst:.1e}")
if worst > 1e-9:
    raise SystemExit("the LAMMPS deck is not rupture's model: its forces differ by more than 1e-9")
PY
[ "$check_only" = 1 ] && exit 0

# 2. Speed.
echo "speed: $preset (seed 1), $steps steps at 50 mm/s, all bonds intact"
echo "| code | workers | wall [s] | particle-steps/s |"
echo "|---|---|---|---|"
for threads in 1 2; do
  "$rupture" bench --run "$config" --set sample.preset="$preset" --threads "$threads" --set loading.speed=50 --set stop.max_steps="$steps" --json \
    | python3 -c "import json,sys; r=json.load(sys.stdin)['results'][0]; print(f\"| rupture | {r['threads']} threads | {r['wall_time']['value']:.2f} | {r['throughput']['value']:.3g} |\")"
done
for ranks in 1 2; do
  mpirun -np "$ranks" lmp "${deck[@]}" -var breaking /dev/null -var steps "$steps" -var speed 50 -var kc "$kc" \
    -var curve lammps-speed.txt > lammps.out
  awk -v ranks="$ranks" '/^Loop time of/ {printf "| LAMMPS | %d ranks | %.2f | %.3g |\n", ranks, $4, $12 * $9 / $4}' lammps.out
done
