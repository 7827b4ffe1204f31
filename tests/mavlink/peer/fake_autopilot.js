#!/usr/bin/env node
// A fake PX4 / ArduPilot autopilot on node-mavlink, the other end of cover-fc-bridge in
// tests: an independent MAVLink implementation that checks every frame the bridge sends.
//
//   node fake_autopilot.js --port P --autopilot px4|ardupilot --sysid N --duration-s S
//                          [--no-heartbeat-after-s T] [--land-s L]
//
// Contract:
// - Binds UDP 127.0.0.1:P and sends to whoever sent to it last (the bridge connects with
//   udpout://127.0.0.1:P and speaks first). Nothing is sent before a peer is known.
// - As system N, component 1 (MAVLink v2, unsigned) it sends HEARTBEAT at 1 Hz (type 2
//   quadrotor, autopilot 12 for px4 / 3 for ardupilot, base_mode 1 | 128 when armed,
//   custom_mode the current mode, system_status 3 standby / 4 active when armed),
//   ATTITUDE_QUATERNION at 50 Hz (level, at rest), EXTENDED_SYS_STATE at 5 Hz (landed
//   state 1 on ground when disarmed, 2 in air when armed, 4 landing), SYS_STATUS at 1 Hz
//   (16.0 V) and answers a TIMESYNC request (tc1 0) with tc1 = its clock in ns.
// - Starts disarmed in PX4 POSCTL (custom_mode 0x00030000) / ArduPilot STABILIZE (0).
// - Answers every COMMAND_LONG addressed to it (target N) with COMMAND_ACK (target: the
//   sender), and records {command, param1, param2, result}:
//     DO_SET_MODE (176), param1 1: px4 param2 = main mode (param3 = sub mode),
//       ardupilot param2 = mode number. OFFBOARD (px4 6) / GUIDED_NOGPS (ardupilot 20) is
//       accepted (0) only when SET_ATTITUDE_TARGET has been streaming faster than 2 Hz
//       (no gap >= 0.5 s) for >= 1 s; otherwise refused: px4 1 (temporarily rejected),
//       ardupilot 2 (denied). Other modes are accepted; param1 without the custom flag: 2.
//     COMPONENT_ARM_DISARM (400): param1 1 arms, 0 disarms (accepted); it never arms
//       unless asked.
//     SET_MESSAGE_INTERVAL (511): accepted (its streams stay as above).
//     NAV_LAND (21): accepted; mode becomes px4 AUTO.LAND (main 4, sub 6) / ardupilot
//       LAND (9); after L s (--land-s, default 2) it disarms, on the ground.
//     anything else: 3 (unsupported).
//   In px4 OFFBOARD with no setpoint for 1 s (COM_OF_LOSS_T) it switches to AUTO.LAND as
//   PX4's failsafe does without a position (event "offboard_lost").
// - Checks every frame it receives: checksum (node-mavlink's splitter), and for
//   SET_ATTITUDE_TARGET: type_mask == 128, target_system == N, target_component == 1,
//   thrust finite in [0, 1], finite body rates. A failed check is a bad frame.
// - --no-heartbeat-after-s T: from T s after start it sends nothing more (a silent
//   autopilot: link lost), but still receives and checks.
// - Runs for S s (--duration-s), or until SIGTERM / SIGINT, then prints one JSON line on
//   stdout and exits 0:
//     {autopilot, sysid, setpoints, setpoint_rate_hz (over the stream's span),
//      bad_frames: [reasons, first 100], bad_frame_count, crc_errors,
//      commands: [{command, param1, param2, result}], first_setpoint_before_offboard
//      (the first setpoint came before the first OFFBOARD / GUIDED_NOGPS request; true
//      with setpoints and no such request, false without setpoints),
//      rate_sums: {roll, pitch, yaw}, last_setpoint: {time_boot_ms, roll_rate,
//      pitch_rate, yaw_rate, thrust} or null, armed, mode (custom_mode), mode_name,
//      events: [{t_s, event}]}
//   Exit 2 on a bad command line (the reason on stderr).
'use strict'
const dgram = require('dgram')
const { MavLinkPacketSplitter, MavLinkPacketParser, MavLinkProtocolV2, minimal, common } =
    require('node-mavlink')

const MAV_CMD_NAV_LAND = 21
const MAV_CMD_DO_SET_MODE = 176
const MAV_CMD_COMPONENT_ARM_DISARM = 400
const MAV_CMD_SET_MESSAGE_INTERVAL = 511
const PX4_MAIN_OFFBOARD = 6
const PX4_MAIN_AUTO = 4
const PX4_SUB_LAND = 6
const COPTER_GUIDED_NOGPS = 20
const COPTER_LAND = 9
const MAX_BAD_FRAMES_LISTED = 100

function usage(reason) {
  process.stderr.write(`fake_autopilot: ${reason}\n` +
    'usage: node fake_autopilot.js --port P --autopilot px4|ardupilot --sysid N ' +
    '--duration-s S [--no-heartbeat-after-s T] [--land-s L]\n')
  process.exit(2)
}

function parseArgs(argv) {
  const options = { port: null, autopilot: null, sysid: null, durationS: null,
                    silentAfterS: Infinity, landS: 2 }
  const numbers = { '--port': 'port', '--sysid': 'sysid', '--duration-s': 'durationS',
                    '--no-heartbeat-after-s': 'silentAfterS', '--land-s': 'landS' }
  for (let i = 0; i < argv.length; i += 2) {
    const flag = argv[i]
    const value = argv[i + 1]
    if (value === undefined) usage(`${flag} needs a value`)
    if (flag === '--autopilot') options.autopilot = value
    else if (numbers[flag]) options[numbers[flag]] = Number(value)
    else usage(`unknown flag ${flag}`)
  }
  if (!Number.isInteger(options.port) || options.port < 1 || options.port > 65535) usage('--port 1..65535')
  if (!['px4', 'ardupilot'].includes(options.autopilot)) usage('--autopilot px4|ardupilot')
  if (!Number.isInteger(options.sysid) || options.sysid < 1 || options.sysid > 255) usage('--sysid 1..255')
  if (!(options.durationS > 0)) usage('--duration-s > 0')
  if (!(options.silentAfterS >= 0)) usage('--no-heartbeat-after-s >= 0')
  if (!(options.landS >= 0)) usage('--land-s >= 0')
  return options
}

class FakeAutopilot {
  constructor(options) {
    this.o = options
    this.px4 = options.autopilot === 'px4'
    this.start = Date.now()
    this.protocol = new MavLinkProtocolV2(options.sysid, 1)
    this.seq = 0
    this.peer = null
    this.armed = false
    this.mode = this.px4 ? 3 << 16 : 0  // POSCTL / STABILIZE
    this.landingSince = null
    this.setpoints = 0
    this.firstSetpointMs = null
    this.lastSetpointMs = null
    this.streamSinceMs = null  // start of the current run of setpoints without a 0.5 s gap
    this.offboardRequested = false
    this.firstSetpointBeforeOffboard = null
    this.rateSums = { roll: 0, pitch: 0, yaw: 0 }
    this.lastSetpoint = null
    this.badFrames = []
    this.badFrameCount = 0
    this.commands = []
    this.events = []
    this.timers = []
  }

  now() { return Date.now() - this.start }
  silent() { return this.now() >= this.o.silentAfterS * 1000 }
  event(text) { this.events.push({ t_s: this.now() / 1000, event: text }) }

  bad(reason) {
    ++this.badFrameCount
    if (this.badFrames.length < MAX_BAD_FRAMES_LISTED) this.badFrames.push(reason)
  }

  run() {
    this.socket = dgram.createSocket('udp4')
    this.splitter = new MavLinkPacketSplitter()
    this.splitter.pipe(new MavLinkPacketParser()).on('data', (packet) => this.onPacket(packet))
    this.socket.on('message', (bytes, from) => {
      this.peer = { address: from.address, port: from.port }
      this.splitter.write(bytes)
    })
    this.socket.on('error', (error) => {
      process.stderr.write(`fake_autopilot: ${error.message}\n`)
      process.exit(1)
    })
    this.socket.bind(this.o.port, '127.0.0.1')
    this.every(1000, () => { this.sendHeartbeat(); this.sendSysStatus() })
    this.every(20, () => this.sendAttitude())
    this.every(200, () => { this.sendExtendedState(); this.step() })
    this.timers.push(setTimeout(() => this.finish(), this.o.durationS * 1000))
    process.on('SIGTERM', () => this.finish())
    process.on('SIGINT', () => this.finish())
  }

  every(periodMs, action) { this.timers.push(setInterval(action, periodMs)) }

  send(message) {
    if (this.peer === null || this.silent()) return
    const bytes = this.protocol.serialize(message, this.seq)
    this.seq = (this.seq + 1) & 0xff
    this.socket.send(bytes, this.peer.port, this.peer.address)
  }

  sendHeartbeat() {
    const m = new minimal.Heartbeat()
    m.type = 2
    m.autopilot = this.px4 ? 12 : 3
    m.baseMode = 1 | (this.armed ? 128 : 0)
    m.customMode = this.mode
    m.systemStatus = this.armed ? 4 : 3
    m.mavlinkVersion = 3
    this.send(m)
  }

  sendSysStatus() {
    const m = new common.SysStatus()
    m.voltageBattery = 16000
    m.currentBattery = this.armed ? 1500 : 50
    m.batteryRemaining = 90
    this.send(m)
  }

  sendAttitude() {
    const m = new common.AttitudeQuaternion()
    m.timeBootMs = this.now()
    m.q1 = 1
    m.reprOffsetQ = [0, 0, 0, 0]
    this.send(m)
  }

  sendExtendedState() {
    const m = new common.ExtendedSysState()
    m.landedState = !this.armed ? 1 : (this.landingSince !== null ? 4 : 2)
    this.send(m)
  }

  // Once every 200 ms: landing completes, offboard loss.
  step() {
    const t = this.now()
    if (this.landingSince !== null && t - this.landingSince >= this.o.landS * 1000) {
      this.landingSince = null
      if (this.armed) this.event('landed, disarmed')
      this.armed = false
    }
    if (this.px4 && this.mainMode() === PX4_MAIN_OFFBOARD &&
        (this.lastSetpointMs === null || t - this.lastSetpointMs >= 1000)) {
      this.setMode(PX4_MAIN_AUTO << 16 | PX4_SUB_LAND << 24)
      this.landingSince = t
      this.event('offboard_lost')
    }
  }

  mainMode() { return (this.mode >> 16) & 0xff }

  setMode(mode) {
    if (mode !== this.mode) this.event(`mode ${modeName(this.px4, mode)}`)
    this.mode = mode
  }

  streamingLongEnough() {
    const t = this.now()
    return this.streamSinceMs !== null && t - this.lastSetpointMs < 500 &&
           t - this.streamSinceMs >= 1000
  }

  onPacket(packet) {
    const id = packet.header.msgid
    if (id === common.SetAttitudeTarget.MSG_ID) {
      this.onSetpoint(packet.protocol.data(packet.payload, common.SetAttitudeTarget))
    } else if (id === common.CommandLong.MSG_ID) {
      this.onCommand(packet.protocol.data(packet.payload, common.CommandLong), packet.header)
    } else if (id === common.TimeSync.MSG_ID) {
      const request = packet.protocol.data(packet.payload, common.TimeSync)
      if (request.tc1 === 0n) {
        const reply = new common.TimeSync()
        reply.tc1 = BigInt(Date.now()) * 1000000n
        reply.ts1 = request.ts1
        reply.targetSystem = packet.header.sysid
        reply.targetComponent = packet.header.compid
        this.send(reply)
      }
    }
  }

  onSetpoint(m) {
    const t = this.now()
    const finite = [m.bodyRollRate, m.bodyPitchRate, m.bodyYawRate].every(Number.isFinite)
    if (m.typeMask !== 128) this.bad(`type_mask ${m.typeMask} != 128`)
    if (m.targetSystem !== this.o.sysid) this.bad(`target_system ${m.targetSystem} != ${this.o.sysid}`)
    if (m.targetComponent !== 1) this.bad(`target_component ${m.targetComponent} != 1`)
    if (!(Number.isFinite(m.thrust) && m.thrust >= 0 && m.thrust <= 1)) this.bad(`thrust ${m.thrust} outside [0, 1]`)
    if (!finite) this.bad('body rate not finite')
    ++this.setpoints
    if (this.firstSetpointBeforeOffboard === null) this.firstSetpointBeforeOffboard = !this.offboardRequested
    if (this.firstSetpointMs === null) this.firstSetpointMs = t
    if (this.lastSetpointMs === null || t - this.lastSetpointMs >= 500) this.streamSinceMs = t
    this.lastSetpointMs = t
    if (finite) {
      this.rateSums.roll += m.bodyRollRate
      this.rateSums.pitch += m.bodyPitchRate
      this.rateSums.yaw += m.bodyYawRate
    }
    this.lastSetpoint = { time_boot_ms: m.timeBootMs, roll_rate: m.bodyRollRate,
                          pitch_rate: m.bodyPitchRate, yaw_rate: m.bodyYawRate, thrust: m.thrust }
  }

  onCommand(m, header) {
    if (m.targetSystem !== this.o.sysid) return
    const result = this.execute(m)
    this.commands.push({ command: m.command, param1: m._param1, param2: m._param2, result })
    const ack = new common.CommandAck()
    ack.command = m.command
    ack.result = result
    ack.targetSystem = header.sysid
    ack.targetComponent = header.compid
    this.send(ack)
  }

  execute(m) {
    switch (m.command) {
      case MAV_CMD_DO_SET_MODE: return this.setModeCommand(m)
      case MAV_CMD_COMPONENT_ARM_DISARM:
        if (m._param1 === 1) { this.armed = true; this.event('armed') } else if (m._param1 === 0) {
          this.armed = false
          this.landingSince = null
          this.event('disarmed')
        } else return 2
        return 0
      case MAV_CMD_SET_MESSAGE_INTERVAL: return 0
      case MAV_CMD_NAV_LAND:
        this.setMode(this.px4 ? (PX4_MAIN_AUTO << 16 | PX4_SUB_LAND << 24) : COPTER_LAND)
        this.landingSince = this.now()
        return 0
      default: return 3
    }
  }

  setModeCommand(m) {
    if ((Math.round(m._param1) & 1) === 0) return 2
    const wanted = Math.round(m._param2)
    const offboard = this.px4 ? wanted === PX4_MAIN_OFFBOARD : wanted === COPTER_GUIDED_NOGPS
    if (offboard) {
      if (this.firstSetpointBeforeOffboard === null) this.firstSetpointBeforeOffboard = false
      this.offboardRequested = true
      if (!this.streamingLongEnough()) return this.px4 ? 1 : 2
    }
    const mode = this.px4 ? (wanted << 16 | (Math.round(m._param3) & 0xff) << 24) : wanted
    this.setMode(mode)
    const landing = this.px4 ? mode === (PX4_MAIN_AUTO << 16 | PX4_SUB_LAND << 24) : mode === COPTER_LAND
    this.landingSince = landing ? this.now() : null
    return 0
  }

  finish() {
    if (this.finished) return
    this.finished = true
    for (const timer of this.timers) { clearInterval(timer); clearTimeout(timer) }
    const crcErrors = this.splitter.invalidPackages
    for (let i = 0; i < crcErrors; ++i) this.bad('checksum')
    const span = (this.lastSetpointMs - this.firstSetpointMs) / 1000
    const summary = {
      autopilot: this.o.autopilot,
      sysid: this.o.sysid,
      setpoints: this.setpoints,
      setpoint_rate_hz: this.setpoints > 1 && span > 0 ? (this.setpoints - 1) / span : 0,
      bad_frames: this.badFrames,
      bad_frame_count: this.badFrameCount,
      crc_errors: crcErrors,
      commands: this.commands,
      first_setpoint_before_offboard: this.setpoints > 0 && this.firstSetpointBeforeOffboard === true,
      rate_sums: this.rateSums,
      last_setpoint: this.lastSetpoint,
      armed: this.armed,
      mode: this.mode,
      mode_name: modeName(this.px4, this.mode),
      events: this.events,
    }
    process.stdout.write(JSON.stringify(summary) + '\n', () => {
      this.socket.close()
      process.exit(0)
    })
  }
}

function modeName(px4, mode) {
  if (px4) {
    const main = (mode >> 16) & 0xff
    const sub = (mode >> 24) & 0xff
    const names = { 1: 'MANUAL', 2: 'ALTCTL', 3: 'POSCTL', 4: 'AUTO', 5: 'ACRO', 6: 'OFFBOARD',
                    7: 'STABILIZED' }
    const subs = { 3: 'LOITER', 6: 'LAND' }
    const name = names[main] || `MAIN_${main}`
    return main === 4 ? `${name}.${subs[sub] || sub}` : name
  }
  const names = { 0: 'STABILIZE', 1: 'ACRO', 2: 'ALT_HOLD', 3: 'AUTO', 4: 'GUIDED', 5: 'LOITER',
                  6: 'RTL', 9: 'LAND', 16: 'POSHOLD', 20: 'GUIDED_NOGPS' }
  return names[mode] || `MODE_${mode}`
}

new FakeAutopilot(parseArgs(process.argv.slice(2))).run()
