// Cross-check against node-mavlink (an independent MAVLink implementation).
//   node interop.mjs OURS.hex
// Prints one line per frame node-mavlink decoded from OURS.hex:
//   decoded <msgid> <seq> <sysid> <compid> <sig-ok|sig-bad|unsigned> <json of the fields>
// and one line with frames node-mavlink encoded for the C++ side to decode:
//   theirs <hex>
// Signing key: bytes 0..31, as in tests/comms/mavlink/node_interop_test.cpp.
import { readFileSync } from 'fs'
import { PassThrough } from 'stream'
import {
  MavLinkPacketSplitter, MavLinkPacketParser, MavLinkProtocolV2, minimal, common
} from 'node-mavlink'

const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY }
const key = Buffer.from([...Array(32).keys()])
const json = (data) => JSON.stringify(data, (k, v) => (typeof v === 'bigint' ? v.toString() : v))

const proto = new MavLinkProtocolV2(7, 9)
const hb = new minimal.Heartbeat()
Object.assign(hb, { type: 10, autopilot: 8, baseMode: 0x81, customMode: 0x01020304,
                    systemStatus: 4, mavlinkVersion: 3 })
const cmd = new common.CommandLong()
Object.assign(cmd, { command: 48101, _param1: -0.75, targetSystem: 1, targetComponent: 1,
                     confirmation: 2 })
const text = new common.StatusText()
Object.assign(text, { severity: 4, text: 'hello from node' })
const odo = new common.Odometry()
Object.assign(odo, { timeUsec: 123456789n, x: 1.25, y: -2.5, q: [1, 0, 0, 0],
                     poseCovariance: Array(21).fill(0), velocityCovariance: Array(21).fill(0),
                     frameId: 20, childFrameId: 12, resetCounter: 3, estimatorType: 1,
                     quality: 77 })
const dist = new common.DistanceSensor()
Object.assign(dist, { timeBootMs: 1000, minDistance: 5, maxDistance: 400, currentDistance: 123,
                      type: 1, id: 6, orientation: 0, covariance: 255, horizontalFov: 0.5,
                      verticalFov: 0, quaternion: [0, 0, 0, 0], signalQuality: 0 })
const frames = [hb, cmd, text, odo, dist].map((m, i) => proto.serialize(m, i + 1))
const signer = new MavLinkProtocolV2(7, 9, MavLinkProtocolV2.IFLAG_SIGNED)
frames.push(signer.sign(signer.serialize(hb, 6), 4, key, 1700000000000))
console.log('theirs', Buffer.concat(frames).toString('hex'))

const input = new PassThrough()
const reader = input.pipe(new MavLinkPacketSplitter()).pipe(new MavLinkPacketParser())
reader.on('data', (p) => {
  const clazz = REGISTRY[p.header.msgid]
  const data = clazz ? p.protocol.data(p.payload, clazz) : null
  const sig = p.signature ? (p.signature.matches(key) ? 'sig-ok' : 'sig-bad') : 'unsigned'
  const h = p.header
  console.log('decoded', h.msgid, h.seq, h.sysid, h.compid, sig, json(data))
})
input.end(Buffer.from(readFileSync(process.argv[2], 'utf8').trim(), 'hex'))
