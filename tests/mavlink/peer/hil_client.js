#!/usr/bin/env node
// A PX4-like simulator_mavlink client on node's net and node-mavlink, the other end of
// COVER's tcpin:// link in tests (tests/mavlink/peer_test.cpp: MavlinkPeer.Tcp*).
//
//   node hil_client.js --port P [--connections C] [--answers A] [--garbage]
//
// Contract, as PX4 SITL's simulator_mavlink: connects to TCP 127.0.0.1:P, retrying every
// 10 ms until the server accepts; as system 2, component 1 sends a HEARTBEAT (type 0,
// autopilot 12) and then, for each HIL_SENSOR it receives, one HIL_ACTUATOR_CONTROLS with
// time_usec = the sensor's time_usec, flags 1 (lockstep), controls[i] = (i + 1) / 16
// (connection 1) or (16 - i) / 16 (later connections), mode 129. After A answers
// (default 3), on the next HIL_SENSOR (the server's sign that it read the last answer) it
// drops the connection (destroys the socket) and connects again, C times (default 2) in all. With --garbage each connection after the first begins with 300 bytes
// that are not MAVLink (0xFD start markers among them) before its HEARTBEAT.
// Prints one JSON line per HIL_SENSOR received: {connection, fields (codec.js naming)},
// and at the end {done: true, connections, crc_errors}. Exit 0; 1 when no server accepted
// within 20 s or a frame failed to decode.
'use strict'
const net = require('net')
const { MavLinkPacketSplitter, MavLinkPacketParser, MavLinkProtocolV2, minimal, common } =
    require('node-mavlink')
const { toJson } = require('./codec')

function option(name, fallback) {
  const i = process.argv.indexOf(name)
  return i >= 0 && i + 1 < process.argv.length ? Number(process.argv[i + 1]) : fallback
}

const PORT = option('--port', NaN)
const CONNECTIONS = option('--connections', 2)
const ANSWERS = option('--answers', 3)
const GARBAGE = process.argv.includes('--garbage')
const protocol = new MavLinkProtocolV2(2, 1)
let seq = 0
let crcErrors = 0
const started = Date.now()

function frame(message) {
  return protocol.serialize(message, seq++ & 0xff)
}

function garbage() {
  const bytes = Buffer.alloc(300)
  for (let i = 0; i < bytes.length; ++i) bytes[i] = (i * 73 + 11) & 0xff
  for (let i = 0; i < bytes.length; i += 37) bytes[i] = 0xfd
  return bytes
}

function connect(index) {
  if (index > CONNECTIONS) {
    process.stdout.write(JSON.stringify({ done: true, connections: CONNECTIONS,
                                          crc_errors: crcErrors }) + '\n')
    process.exit(0)
  }
  const socket = net.connect({ host: '127.0.0.1', port: PORT })
  socket.setNoDelay(true)
  socket.on('error', () => {
    socket.destroy()
    if (Date.now() - started > 20000) {
      process.stderr.write('hil_client: no server accepted within 20 s\n')
      process.exit(1)
    }
    setTimeout(() => connect(index), 10)
  })
  socket.on('connect', () => {
    if (GARBAGE && index > 1) socket.write(garbage())
    const hello = new minimal.Heartbeat()
    hello.type = 0
    hello.autopilot = 12
    hello.baseMode = 0
    hello.systemStatus = 0
    hello.mavlinkVersion = 3
    socket.write(frame(hello))
    let answers = 0
    let closing = false
    const splitter = new MavLinkPacketSplitter()
    socket.pipe(splitter).pipe(new MavLinkPacketParser()).on('data', (packet) => {
      if (packet.header.msgid !== common.HilSensor.MSG_ID || closing) return
      if (answers === ANSWERS) {
        // The server sends its next sensor frame only after it has read our last answer:
        // dropping the connection before that could lose the answer in the server's socket
        // when it accepts the new connection first.
        closing = true
        crcErrors += splitter.invalidPackages
        socket.end(() => {
          socket.destroy()
          connect(index + 1)
        })
        return
      }
      const sensor = packet.protocol.data(packet.payload, common.HilSensor)
      process.stdout.write(JSON.stringify({ connection: index, fields: toJson(sensor) }) + '\n')
      const answer = new common.HilActuatorControls()
      answer.timeUsec = sensor.timeUsec
      answer.flags = 1n
      answer.controls = Array.from({ length: 16 },
                                   (_, i) => (index === 1 ? i + 1 : 16 - i) / 16)
      answer.mode = 129
      socket.write(frame(answer))
      ++answers
    })
  })
}

if (!Number.isInteger(PORT)) {
  process.stderr.write('usage: node hil_client.js --port P [--connections C] [--answers A] [--garbage]\n')
  process.exit(2)
}
connect(1)
