#!/usr/bin/env bash
# Issue 24's acceptance matrix on the wall clock: map building through real processes —
# irgs-sim --connect -> irgs-linkem -> irgs-robot --tcp — against the same mission in-process,
# for each map x protocol x link case. Prints one TSV row per run (and writes DIR/matrix.tsv):
#   map protocol case robot_s inprocess_s ratio f1_truth f1_vs_inprocess obstacles lost_too_soon
# Link cases: a (no delay), b (150 ms + 0-100 ms), c (400 ms + 0-200 ms, 0.5 s stalls every
# 20 s), d (9600 baud, MAVLink's compact telemetry; ARCOS is at 9600 in every case).
#
#   scripts/link_matrix.sh [--build DIR] [--out DIR] [--maps "M1 M2"] [--protocols "mavlink arcos"]
#                          [--cases "a b c d"] [--seed N] [--jobs N] [--duration S]
# Each run takes its robot time on the wall clock (2-7 min); --jobs runs that many at once
# (they are mostly idle: 2 fit a 2-core machine). Default noise; the same --seed in-process.
set -euo pipefail

here="$(cd "$(dirname "$0")/.." && pwd)"
build="$here/build"
out="$PWD/link_matrix"
maps="$here/resources/maps/thesis_arena_250.json"
protocols="mavlink arcos"
cases="a b c d"
seed=1
jobs=2
duration=900
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --maps) maps="$2"; shift 2 ;;
    --protocols) protocols="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --duration) duration="$2"; shift 2 ;;
    *) echo "link_matrix.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
sim="$build/app/sim/irgs-sim"
robot="$build/app/robot/irgs-robot"
linkem="$build/app/tools/irgs-linkem"
for exe in "$sim" "$robot" "$linkem"; do
  [ -x "$exe" ] || { echo "link_matrix.sh: $exe not built (--build DIR)" >&2; exit 2; }
done
mkdir -p "$out"

profile_of() {  # protocol -> robot profile
  if [ "$1" = arcos ]; then echo "$here/resources/robots/pioneer_amigo.json"
  else echo "$here/resources/robots/thesis_robot.json"; fi
}

# metrics.json -> "robot_s f1_truth f1_vs_inprocess obstacles"
figures() {
  python3 - "$1" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
f1 = lambda k: (m.get(k) or {}).get("f1", float("nan"))
done = (m.get("behaviour") or {}).get("finished") and not m["behaviour"].get("failed")
print(f'{m["duration_s"]:.1f} {f1("map_score"):.3f} {f1("map_agreement"):.3f} '
      f'{(m.get("map_building") or {}).get("obstacles", "?")}{"" if done else "(unfinished)"}')
EOF
}

inprocess() {  # map protocol -> DIR with the in-process run
  local name dir
  name="$(basename "${1%.*}")"
  dir="$out/$name-$2-inprocess"
  if [ ! -f "$dir/metrics.json" ]; then
    "$sim" --map "$1" --robot "$(profile_of "$2")" --seed "$seed" --behaviour mapbuild \
      --duration "$duration" --out "$dir" --quiet
  fi
  echo "$dir"
}

port_of() {  # "irgs-robot: ... tcp PORT" / "linkem: listening on HOST:PORT"
  local file="$1" pattern="$2"
  for _ in $(seq 100); do
    if grep -q "$pattern" "$file" 2>/dev/null; then
      grep -o "$pattern[0-9.:]*" "$file" | head -1 | sed 's/.*://; s/.* //'
      return
    fi
    sleep 0.1
  done
  echo "link_matrix.sh: no port in $file" >&2
  return 1
}

one_run() {  # map protocol case
  local map="$1" protocol="$2" case="$3" name dir local_dir baud robot_args url url_extra link_args
  name="$(basename "${map%.*}")"
  dir="$out/$name-$protocol-$case"
  local_dir="$(inprocess "$map" "$protocol")"
  rm -rf "$dir" && mkdir -p "$dir"
  baud=115200
  robot_args=()
  url_extra=""
  if [ "$protocol" = arcos ]; then
    baud=9600
    robot_args=(--protocol arcos --strict)
    url_extra="&protocol=arcos"
  fi
  case "$case" in
    a) link_args=(--delay-ms 0 --jitter-ms 0) ;;
    b) link_args=(--delay-ms 150 --jitter-ms 100) ;;
    c) link_args=(--delay-ms 400 --jitter-ms 200 --stall-every-s 20 --stall-ms 500) ;;
    d) link_args=(--delay-ms 0 --jitter-ms 0); baud=9600 ;;
    *) echo "link_matrix.sh: unknown case $case" >&2; return 2 ;;
  esac
  "$robot" "${robot_args[@]}" --map "$map" --robot "$(profile_of "$protocol")" --seed "$seed" \
    --tcp 127.0.0.1:0 --baud "$baud" > "$dir/robot.log" 2>&1 &
  local robot_pid=$!
  local robot_port link_port
  robot_port="$(port_of "$dir/robot.log" "tcp ")"
  "$linkem" --listen 127.0.0.1:0 --connect "127.0.0.1:$robot_port" "${link_args[@]}" \
    --baud "$baud" --seed "$seed" > "$dir/linkem.log" 2>&1 &
  local linkem_pid=$!
  link_port="$(port_of "$dir/linkem.log" "listening on 127.0.0.1:")"
  url="tcp://127.0.0.1:$link_port?baud=$baud$url_extra"
  local code=0
  "$sim" --connect "$url" --map "$map" --robot "$(profile_of "$protocol")" --behaviour mapbuild \
    --compare "$local_dir/grid.yaml" --duration "$duration" --out "$dir/out" \
    > "$dir/sim.log" 2>&1 || code=$?
  kill -INT "$robot_pid" 2>/dev/null || true
  sleep 1
  kill "$linkem_pid" 2>/dev/null || true
  wait "$robot_pid" "$linkem_pid" 2>/dev/null || true
  local lost="-"
  [ "$protocol" = arcos ] && lost="$(grep -o 'lost too soon [0-9]*' "$dir/robot.log" | awk '{print $4}')"
  if [ "$code" -ne 0 ] || [ ! -f "$dir/out/metrics.json" ]; then
    printf '%s\t%s\t%s\tfailed (exit %s, %s/sim.log)\n' "$name" "$protocol" "$case" "$code" "$dir"
    return
  fi
  read -r robot_s f1 agree obstacles < <(figures "$dir/out/metrics.json")
  read -r local_s _ _ _ < <(figures "$local_dir/metrics.json")
  printf '%s\t%s\t%s\t%s\t%s\t%.2f\t%s\t%s\t%s\t%s\n' "$name" "$protocol" "$case" "$robot_s" \
    "$local_s" "$(awk "BEGIN {print $robot_s / $local_s}")" "$f1" "$agree" "$obstacles" "$lost"
}

export -f one_run inprocess figures port_of profile_of
export here out seed duration sim robot linkem
printf 'map\tprotocol\tcase\trobot_s\tinprocess_s\tratio\tf1_truth\tf1_vs_inprocess\tobstacles\tlost_too_soon\n' \
  | tee "$out/matrix.tsv"
runs=()
for map in $maps; do
  for protocol in $protocols; do
    inprocess "$map" "$protocol" > /dev/null  # once, before the parallel runs share it
    for case in $cases; do
      [ "$protocol" = arcos ] && [ "$case" = d ] && continue  # ARCOS is at 9600 in every case
      runs+=("$map $protocol $case")
    done
  done
done
printf '%s\n' "${runs[@]}" | xargs -P "$jobs" -I{} bash -c 'one_run {}' | tee -a "$out/matrix.tsv"
