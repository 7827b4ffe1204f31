#!/usr/bin/env node
// Writes, with node-mavlink, frames of each of the 17 messages COVER's codec speaks, for
// the C++ parser to read (tests/mavlink/peer_test.cpp: MavlinkPeer.ParsesNodeFrames).
//
//   node write_frames.js --frames OUT.bin --values OUT.json
//
// OUT.bin: the frames back to back: every message unsigned v2, signed v2 (test_key.js,
// link id 3, fixed timestamps) and, for the messages without extensions, v1. OUT.json:
// one entry per frame in order: {message, id, version, signed, seq, sysid, compid,
// fields} with the field values as node-mavlink decodes them from its own frame (so
// floats are the float32 values on the wire). Exit 0, or 1 with the reason on stderr.
'use strict'
const fs = require('fs')
const { MavLinkProtocolV1, MavLinkProtocolV2 } = require('node-mavlink')
const { MESSAGES, fromJson, toJson } = require('./codec')
const { KEY } = require('./test_key')

// Non-trivial values: negatives, extremes of each type, every extension set, and for
// some messages trailing zeros (trimmed on the wire).
const VALUES = {
  HEARTBEAT: { custom_mode: 0x00060000, type: 2, autopilot: 12, base_mode: 129,
               system_status: 4, mavlink_version: 3 },
  SYS_STATUS: { onboard_control_sensors_present: 0xdeadbeef, onboard_control_sensors_enabled: 7,
                onboard_control_sensors_health: 0x80000001, load: 512, voltage_battery: 16123,
                current_battery: -1234, drop_rate_comm: 3, errors_comm: 65535,
                errors_count1: 1, errors_count2: 2, errors_count3: 3, errors_count4: 4,
                battery_remaining: -1, onboard_control_sensors_present_extended: 11,
                onboard_control_sensors_enabled_extended: 22,
                onboard_control_sensors_health_extended: 33 },
  SCALED_IMU: { time_boot_ms: 4000000000, xacc: -981, yacc: 12, zacc: 32767, xgyro: -32768,
                ygyro: 5, zgyro: -6, xmag: 100, ymag: -200, zmag: 300, temperature: -2150 },
  ATTITUDE_QUATERNION: { time_boot_ms: 123456, q1: 0.7071068, q2: -0.7071068, q3: 0.001,
                         q4: -1e-7, rollspeed: 1.5, pitchspeed: -2.25, yawspeed: 3.125,
                         repr_offset_q: [0.5, -0.5, 0.25, 1e-20] },
  COMMAND_LONG: { param: [1, 6, -1.5, 3.4e38, 0, 1e-3, -7], command: 176, target_system: 42,
                  target_component: 1, confirmation: 2 },
  COMMAND_ACK: { command: 400, result: 2, progress: 100, result_param2: -123456789,
                 target_system: 245, target_component: 190 },
  SET_ATTITUDE_TARGET: { time_boot_ms: 1000, q: [1, 0, 0, 0], body_roll_rate: 0.1,
                         body_pitch_rate: -0.2, body_yaw_rate: 0.3, thrust: 0.5,
                         target_system: 1, target_component: 1, type_mask: 128,
                         thrust_body: [0, 0, 0] },
  ATTITUDE_TARGET: { time_boot_ms: 99, q: [0.5, 0.5, -0.5, 0.5], body_roll_rate: -0.01,
                     body_pitch_rate: 0.02, body_yaw_rate: -3.14159, thrust: 0.73,
                     type_mask: 7 },
  HIGHRES_IMU: { time_usec: '18446744073709551000', xacc: 0.1, yacc: -0.2, zacc: -9.81,
                 xgyro: 0.01, ygyro: -0.02, zgyro: 0.03, xmag: 0.2, ymag: -0.1, zmag: 0.45,
                 abs_pressure: 1013.25, diff_pressure: -0.5, pressure_alt: 488.5,
                 temperature: 36.6, fields_updated: 0x1fff, id: 2 },
  TIMESYNC: { tc1: '-9223372036854775000', ts1: '1700000000123456789', target_system: 42,
              target_component: 1 },
  BATTERY_STATUS: { current_consumed: -1, energy_consumed: 123456, temperature: 32767,
                    voltages: [4100, 4110, 4120, 4130, 65535, 65535, 65535, 65535, 65535, 65535],
                    current_battery: 2500, id: 1, battery_function: 1, type: 1,
                    battery_remaining: 87, time_remaining: 600, charge_state: 1,
                    voltages_ext: [0, 1, 2, 3], mode: 2, fault_bitmask: 0x80000000 },
  EXTENDED_SYS_STATE: { vtol_state: 0, landed_state: 2 },
  STATUSTEXT: { severity: 4, text: 'Offboard: no setpoints for 0.5 s, holding attitude',
                id: 513, chunk_seq: 7 },
  HIL_SENSOR: { time_usec: '18446744073709551000', xacc: 0.25, yacc: -0.5, zacc: -9.80665,
                xgyro: 0.001, ygyro: -0.002, zgyro: 3.5, xmag: 0.216, ymag: 0.009, zmag: 0.426,
                abs_pressure: 955.5, diff_pressure: -0.125, pressure_alt: 488.25,
                temperature: 11.8, fields_updated: 7167, id: 2 },
  // flags before controls on the wire: a codec that swaps them reads other values here
  HIL_ACTUATOR_CONTROLS: { time_usec: '1234567890123', flags: '9223372036854775809',
                           controls: [0.5, -0.5, 1, 0, 0.25, -1, 0.125, 0, 0, 0, 0, 0, 0, 0,
                                      -0.75, 0.875],
                           mode: 129 },
  HIL_STATE_QUATERNION: { time_usec: '4000000123', attitude_quaternion: [0.5, -0.5, 0.5, -0.5],
                          rollspeed: 0.1, pitchspeed: -0.2, yawspeed: 0.3, lat: 473977418,
                          lon: -85455939, alt: -2147483648, vx: -32768, vy: 32767, vz: -5,
                          ind_airspeed: 65535, true_airspeed: 1200, xacc: -1000, yacc: 12,
                          zacc: 999 },
  HIL_GPS: { time_usec: '77', lat: -473977418, lon: 1799999999, alt: 488000, eph: 80, epv: 120,
             vel: 150, vn: -100, ve: 110, vd: -7, cog: 35999, fix_type: 3,
             satellites_visible: 12, id: 1, yaw: 9000 },
}

const V1_MESSAGES = ['HEARTBEAT', 'COMMAND_LONG', 'ATTITUDE_TARGET', 'EXTENDED_SYS_STATE']
const SIGNING_LINK_ID = 3
const SIGNING_START_MS = Date.UTC(2026, 0, 1)

function arg(name) {
  const i = process.argv.indexOf(name)
  if (i < 0 || i + 1 >= process.argv.length) {
    process.stderr.write(`write_frames: ${name} FILE is required\n`)
    process.exit(1)
  }
  return process.argv[i + 1]
}

function entry(buffer, name, version, signed, seq, sysid, compid) {
  const protocol = version === 1 ? new MavLinkProtocolV1() : new MavLinkProtocolV2()
  const header = protocol.header(buffer)
  const data = protocol.data(protocol.payload(buffer), MESSAGES[name])
  return { message: name, id: MESSAGES[name].MSG_ID, version, signed, seq, sysid, compid,
           payload_length: header.payloadLength, fields: toJson(data) }
}

function main() {
  const framesPath = arg('--frames')
  const valuesPath = arg('--values')
  const buffers = []
  const entries = []
  let seq = 0
  let signedCount = 0
  for (const [name, fields] of Object.entries(VALUES)) {
    const clazz = MESSAGES[name]
    const unsigned = new MavLinkProtocolV2(1, 1).serialize(fromJson(clazz, fields), seq)
    buffers.push(unsigned)
    entries.push(entry(unsigned, name, 2, false, seq++, 1, 1))

    const plain = new MavLinkProtocolV2(42, 200, MavLinkProtocolV2.IFLAG_SIGNED)
    const signed = plain.sign(plain.serialize(fromJson(clazz, fields), seq), SIGNING_LINK_ID,
                              KEY, SIGNING_START_MS + signedCount++)
    buffers.push(signed)
    entries.push(entry(signed, name, 2, true, seq++, 42, 200))

    if (V1_MESSAGES.includes(name)) {
      const v1 = new MavLinkProtocolV1(7, 9).serialize(fromJson(clazz, fields), seq)
      buffers.push(v1)
      entries.push(entry(v1, name, 1, false, seq++, 7, 9))
    }
  }
  fs.writeFileSync(framesPath, Buffer.concat(buffers))
  fs.writeFileSync(valuesPath, JSON.stringify(entries, null, 1))
}

main()
