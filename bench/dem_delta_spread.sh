#!/usr/bin/env bash
# δ_x's reported uncertainty against its spread on real DEM runs (docs/analysis.md): the default
# study's reduced tissue run with curve rows every 50, 100 and 200 steps (sample seed 1), and with
# sample seeds 1-5 (rows every 100 steps); each curve analysed with default options.
# Usage: bench/dem_delta_spread.sh [RUPTURE] [OUT]   (default build/release/bin/rupture, /tmp/dem-delta)
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
rupture=${1:-$top/build/release/bin/rupture}
out=${2:-/tmp/dem-delta}
mkdir -p "$out"
cat > "$out/base.toml" <<'TOML'
[sample]
preset = "tissue-small"
seed = 1
density = 2.5e-4
[bonds]
stiffness = 1e3
break_distance = 0.005
[loading]
speed = 50.0
ramp_steps = 10000
[stop]
extra_strain = 0.3
max_strain = 1.5
[output]
interval = 200
[run]
threads = 2
TOML
printf '| sample seed | rows every (steps) | rows | noise | x_p [%%] | x_c [%%] | δ_x [%%] | sd [%%] | 95 %% interval [%%] | accepted | x_p sd [%%] | x_p 95 %% [%%] | E_e white [%% of E_max] |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
run_one() {
  local seed=$1 interval=$2 dir="$out/seed$1-every$2"
  if [ ! -f "$dir/curves.csv" ] || [ ! -f "$dir/run.json" ] || ! grep -q '"finished"' "$dir/run.json"; then
    rm -rf "$dir"
    "$rupture" run "$out/base.toml" --set sample.seed="$seed" --set output.interval="$interval" -o "$dir" > "$dir.log" 2>&1 || true
  fi
  "$rupture" analyze "$dir/curves.csv" -o "$dir/analysis.json" > /dev/null 2>&1 || true
  python3 - "$dir/analysis.json" "$seed" "$interval" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); d = j.get("delta_x") or {}
f = lambda k: (j.get(k) or {}).get("value", float("nan"))
x_p = j.get("x_p") or {}
white = ((j.get("uncertainty") or {}).get("noise") or {}).get("elastic_energy", {}).get("white_sd", {}).get("value")
share = 100 * white / f("E_max") if white is not None and f("E_max") > 0 else float("nan")
mark = lambda q: "" if ((q or {}).get("interval_scales") or {}).get("calibrated") else " (not calibrated)"
print("| %s | %s | %d | %s | %.4f | %.4f | %.4f | %.4f | [%.4f, %.4f]%s | %s | %.4f | [%.4f, %.4f]%s | %.3f |" % (
      sys.argv[2], sys.argv[3], j["resample"]["input_rows"], (d.get("interval_scales") or {}).get("noise", "-"),
      f("x_p"), f("x_c"), d.get("value", float("nan")), d.get("sd", float("nan")),
      *(d.get("ci95") or [float("nan")] * 2), mark(d), "yes" if j["accepted"] else "no: " + j["rejection"],
      x_p.get("error", float("nan")), *(x_p.get("ci95") or [float("nan")] * 2), mark(x_p), share))
PY
}
for interval in 50 100 200; do run_one 1 "$interval"; done
for seed in 2 3 4 5; do run_one "$seed" 100; done
