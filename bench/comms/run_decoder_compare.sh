#!/usr/bin/env bash
# FrameDecoder against node-mavlink 2.3.0 on the same bytes, in one run (issue 3 acceptance:
# >= 10x). Writes the mixed telemetry stream once, runs the Google Benchmark program and the node
# reference on it, prints both medians and their ratio; exits 1 when the ratio is below 10.
#
#   bench/comms/run_decoder_compare.sh [BUILD_DIR]      (default: build)
#
# Needs the irgs_bench_decoder target built in BUILD_DIR, node and npm (node-mavlink is installed
# with npm into BUILD_DIR/bench/comms/node_reference on first use).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-build}"
bench="$build/bench/comms/irgs_bench_decoder"
if [[ ! -x "$bench" ]]; then
  echo "run_decoder_compare: $bench not built (cmake --build $build --target irgs_bench_decoder)" >&2
  exit 2
fi
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "run_decoder_compare: node and npm are needed for the node-mavlink reference" >&2
  exit 2
fi

work="$(cd "$build" && pwd)/bench/comms/node_reference"
mkdir -p "$work"
cp "$here/node_decoder_bench.mjs" "$work/"
if [[ ! -d "$work/node_modules/node-mavlink" ]]; then
  echo "installing node-mavlink@2.3.0 into $work ..."
  (cd "$work" && npm install --no-audit --no-fund node-mavlink@2.3.0 >npm.log 2>&1) || {
    echo "run_decoder_compare: npm install failed, see $work/npm.log" >&2
    exit 2
  }
fi

"$bench" --write-stream "$work/stream.bin"
"$bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$work/cpp.json" --benchmark_out_format=json
(cd "$work" && node node_decoder_bench.mjs stream.bin 9 4096) | tee "$work/node.txt"

# Compare the medians (node parses the JSON; it is here anyway).
node - "$work/cpp.json" "$work/node.txt" "$work/stream.bin" <<'EOF'
const fs = require('fs')
const [cppPath, nodePath, streamPath] = process.argv.slice(2)
const streamBytes = fs.statSync(streamPath).size
const cpp = {}
for (const b of JSON.parse(fs.readFileSync(cppPath, 'utf8')).benchmarks) {
  if (b.aggregate_name === 'median') cpp[b.run_name] = b.bytes_per_second / 1e6
}
const node = {}
for (const line of fs.readFileSync(nodePath, 'utf8').trim().split('\n')) {
  const f = line.split(/\s+/)
  node[f[1]] = { median: Number(f[3]), frames: Number(f[9]), bytes: Number(f[11]) }
  if (Number(f[11]) !== streamBytes) { console.error('node read a different stream'); process.exit(1) }
}
const expectedFrames = node.parse.frames
if (node['parse+deserialize'].frames !== expectedFrames) {
  console.error('node frame counts differ between modes'); process.exit(1)
}
const rows = [
  ['BM_FrameDecoder/4096', 'parse', 'framing + CRC'],
  ['BM_FrameDecoderUnpack/4096', 'parse+deserialize', 'framing + CRC + typed messages'],
]
let worst = Infinity
console.log(`\nstream: ${streamBytes} bytes, ${expectedFrames} frames (node-mavlink count)`)
for (const [c, n, what] of rows) {
  const ratio = cpp[c] / node[n].median
  worst = Math.min(worst, ratio)
  console.log(`${what.padEnd(32)} FrameDecoder ${cpp[c].toFixed(1)} MB/s   node-mavlink ` +
              `${node[n].median.toFixed(2)} MB/s   ratio ${ratio.toFixed(1)}x`)
}
for (const c of ['BM_FrameDecoder/64', 'BM_FrameDecoderUnpack/64'])
  console.log(`${c.padEnd(32)} ${cpp[c].toFixed(1)} MB/s (64-byte reads)`)
if (!(worst >= 10)) { console.log(`FAIL: ratio ${worst.toFixed(1)}x < 10x`); process.exit(1) }
console.log(`PASS: FrameDecoder >= 10x node-mavlink (worst ${worst.toFixed(1)}x)`)
EOF
