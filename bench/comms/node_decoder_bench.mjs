// The reference for bench/comms/decoder_bench.cpp: node-mavlink 2.3.0 parsing the same bytes.
//   node node_decoder_bench.mjs STREAM.bin [REPETITIONS] [CHUNK]
// Each repetition pipes the whole stream, CHUNK bytes at a time (default 4096), through
// MavLinkPacketSplitter (framing, CRC with CRC_EXTRA) and MavLinkPacketParser (header/payload
// objects) -- the work FrameDecoder does -- and, in the second measurement, also deserialises
// every payload into its message class (FrameDecoder + typed unpack). Prints one line per mode:
//   node <mode> median_MBps <x> min_MBps <x> max_MBps <x> frames <n> bytes <n>
// (MB = 1e6 bytes, per CPU second of the node process). Frame counts must equal the stream's; the driver checks them.
import { readFileSync } from 'fs'
import { PassThrough } from 'stream'
import {
  MavLinkPacketSplitter, MavLinkPacketParser, minimal, common
} from 'node-mavlink'

const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY }
const bytes = readFileSync(process.argv[2])
const repetitions = Number(process.argv[3] ?? 9)
const chunk = Number(process.argv[4] ?? 4096)

function parseOnce (deserialize) {
  return new Promise((resolve, reject) => {
    let frames = 0
    let sink = 0
    const input = new PassThrough({ highWaterMark: chunk })
    const reader = input.pipe(new MavLinkPacketSplitter()).pipe(new MavLinkPacketParser())
    reader.on('data', (p) => {
      frames++
      if (deserialize) {
        const clazz = REGISTRY[p.header.msgid]
        if (clazz) sink += p.protocol.data(p.payload, clazz) ? 1 : 0
      }
    })
    reader.on('end', () => resolve({ frames, sink }))
    reader.on('error', reject)
    for (let at = 0; at < bytes.length; at += chunk) input.write(bytes.subarray(at, at + chunk))
    input.end()
  })
}

async function measure (deserialize) {
  const rates = []
  let frames = 0
  for (let i = 0; i < repetitions + 2; i++) {  // two warm-up runs for the JIT
    // CPU time of the process (user + system), like Google Benchmark's bytes_per_second, so a
    // busy shared machine does not count against either side.
    const start = process.cpuUsage()
    const r = await parseOnce(deserialize)
    const used = process.cpuUsage(start)
    const seconds = (used.user + used.system) / 1e6
    frames = r.frames
    if (i >= 2) rates.push(bytes.length / seconds / 1e6)
  }
  rates.sort((a, b) => a - b)
  const median = rates[Math.floor(rates.length / 2)]
  const mode = deserialize ? 'parse+deserialize' : 'parse'
  console.log(`node ${mode} median_MBps ${median.toFixed(3)} min_MBps ${rates[0].toFixed(3)} ` +
              `max_MBps ${rates[rates.length - 1].toFixed(3)} frames ${frames} bytes ${bytes.length}`)
}

await measure(false)
await measure(true)
