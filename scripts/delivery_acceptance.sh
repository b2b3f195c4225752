#!/usr/bin/env bash
# Delivery acceptance of paper 002 (issue 7): node 0 -> node 6 on the bundled delivery floor,
# SEEDS seeds without obstacles and with the three scripted moving obstacles, in irgs-sim.
# Prints one row per run and a summary; exits 1 when a requirement fails (all runs succeed
# without obstacles; at least 90 % with them; no collision anywhere).
#   scripts/delivery_acceptance.sh [SEEDS=20] [OBSERVER=ideal] [BUILD_DIR=build]
# IRGS_SIM=path/to/irgs-sim overrides the build folder (ctest does this).
set -euo pipefail
seeds=${1:-20}
observer=${2:-ideal}
build=${3:-build}
here=$(cd "$(dirname "$0")/.." && pwd)
sim=${IRGS_SIM:-$build/app/sim/irgs-sim}
[[ -x $sim ]] || sim="$here/$build/app/sim/irgs-sim"
[[ -x $sim ]] || { echo "delivery_acceptance: no irgs-sim in $build (build it first)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

status=0
printf '%-8s %-6s %4s %7s %6s %10s %8s %10s\n' obstacles seed ok time_s dist_m goal_err_m min_cl_m collisions
for map in delivery_floor_002 delivery_floor_002_people; do
  ok=0 collisions=0
  for ((seed = 1; seed <= seeds; ++seed)); do
    dir="$out/$map-$seed"
    "$sim" --map "$here/resources/maps/$map.json" --robot "$here/resources/robots/delivery_002.json" \
      --behaviour deliver --from 0 --to 6 --observer "$observer" --seed "$seed" --out "$dir" \
      --quiet >/dev/null 2>&1 || true
    row=$(python3 - "$dir/metrics.json" <<'PY'
import json, sys
try:
    d = json.load(open(sys.argv[1]))["delivery"]
except Exception:
    print("0 nan nan nan nan 0")
    sys.exit()
print(int(d["success"]), d["time_s"], d["distance_m"], d["goal_error_m"], d["min_clearance_m"],
      d["collisions"])
PY
)
    read -r s t dist err cl col <<<"$row"
    [[ $map == *people ]] && label=moving || label=none
    printf '%-8s %-6s %4s %7s %6s %10s %8s %10s\n' "$label" "$seed" "$s" "$t" "$dist" "$err" "$cl" "$col"
    ok=$((ok + s))
    collisions=$((collisions + col))
  done
  echo "== $map ($observer observer): $ok of $seeds delivered, $collisions collisions"
  if [[ $map == *people ]]; then
    need=$(( (seeds * 9 + 9) / 10 ))
  else
    need=$seeds
  fi
  if ((ok < need || collisions > 0)); then
    echo "== FAILED: need $need of $seeds and no collision" >&2
    status=1
  fi
done
exit $status
