#!/usr/bin/env bash
# End-to-end: run irgs under a virtual X server with a drive script, take a screenshot after
# some simulated seconds, and check the picture. Exit 77 (ctest SKIP) when xvfb-run is absent.
#   screenshot_test.sh IRGS CHECKER SOURCE_DIR WORK_DIR
set -euo pipefail
irgs=$1 checker=$2 source_dir=$3 work_dir=$4
size=1400x880

if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIP: xvfb-run is not installed (apt install xvfb)"
  exit 77
fi
mkdir -p "$work_dir"
png=$work_dir/screenshot.png
settings=$work_dir/settings.ini
rm -f "$png" "$settings"

# --quit-after is only a guard against a hung run; the screenshot comes after 6 s of sim time.
xvfb-run -a -s "-screen 0 1600x1000x24" "$irgs" \
  --settings "$settings" \
  --map "$source_dir/resources/maps/default.json" \
  --drive-script "$source_dir/tests/e2e/data/explore_default.txt" \
  --window-size "$size" \
  --screenshot "$png" --screenshot-after 6 --quit-after 90

test -f "$png" || { echo "FAIL: no screenshot written"; exit 1; }
"$checker" "$png" "$size"
