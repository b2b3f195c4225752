#!/usr/bin/env bash
# IRGS quick start. Two jobs, each self-contained on a fresh Debian 12 machine:
#   scripts/quickstart.sh run    install what is missing, build, launch the GUI in simulator mode
#                                on the bundled default map (headless: run the default scenario
#                                through irgs-sim and print where the outputs went)
#   scripts/quickstart.sh test   install what is missing, build, run the whole test suite (ctest)
# Environment: BUILD_DIR (default: build), JOBS (default: nproc), CI (true => -Werror),
# IRGS_BENCH_MRPT=1 (also install libmrpt-dev for the MRPT benchmark).
set -euo pipefail

job=${1:-}
case "$job" in
  run | test) ;;
  *)
    echo "usage: $0 run|test" >&2
    exit 2
    ;;
esac

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
jobs=${JOBS:-$(nproc)}

packages=(build-essential cmake ninja-build pkg-config
  qt6-base-dev qt6-charts-dev qt6-svg-dev libqt6sql6-sqlite libgl-dev libqt6opengl6-dev
  libeigen3-dev libboost-dev libboost-system-dev libboost-graph-dev
  libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libyaml-cpp-dev libopencv-dev
  libsdl2-dev xvfb xauth socat mold)
# Benchmark-only: MRPT for bench/mapping's sonar insertion comparison (irgs_bench_mrpt_grid).
# Opt in with IRGS_BENCH_MRPT=1; the normal build and the tests never need it.
if [ "${IRGS_BENCH_MRPT:-}" = 1 ]; then packages+=(libmrpt-dev); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing missing Debian packages: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

# Warnings are errors under CI only; locally the cached choice stands (switching it would
# rebuild everything).
# Line tables only (-g1): backtraces keep file:line, the clean build is a good part faster;
# configure by hand with -DIRGS_DEBUG_INFO=full to step through in gdb.
cmake_args=(-G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIRGS_DEBUG_INFO=lines)
if [ "${CI:-}" = "true" ] || [ "${CI:-}" = "1" ]; then cmake_args+=(-DIRGS_WERROR=ON); fi

echo "== configuring ($build_dir)"
cmake -S "$root" -B "$build_dir" "${cmake_args[@]}" >/dev/null
echo "== building with $jobs jobs"
cmake --build "$build_dir" -j "$jobs"

if [ "$job" = test ]; then
  echo "== running the test suite"
  cd "$build_dir"
  # One test more than cores: the longest e2e tests (map building behind a late link, minutes
  # of robot time on the wall clock) mostly wait, and would otherwise hold a core each.
  QT_QPA_PLATFORM=offscreen ctest --output-on-failure -j "$((jobs + 1))" --timeout 600
  exit $?
fi

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  echo "== launching irgs (simulator mode, bundled default map)"
  exec "$build_dir/app/gui/irgs" --map "$root/resources/maps/default.json"
fi

out=$root/out/default
echo "== no display: running the default scenario headless"
"$build_dir/app/sim/irgs-sim" --map "$root/resources/maps/default.json" \
  --script "$root/resources/scenarios/default_drive.txt" --seed 1 --out "$out"
echo "== outputs written to $out:"
ls -1 "$out" | sed 's/^/   /'
