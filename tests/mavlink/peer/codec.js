// The 17 messages COVER's codec speaks, as node-mavlink classes, and their values as JSON
// in the C++ structs' field names (snake_case; COMMAND_LONG's param1..7 as `param`;
// 64-bit integers as decimal strings, since JSON numbers cannot hold them exactly).
'use strict'
const { minimal, common } = require('node-mavlink')

const MESSAGES = {
  HEARTBEAT: minimal.Heartbeat,
  SYS_STATUS: common.SysStatus,
  SCALED_IMU: common.ScaledImu,
  ATTITUDE_QUATERNION: common.AttitudeQuaternion,
  COMMAND_LONG: common.CommandLong,
  COMMAND_ACK: common.CommandAck,
  SET_ATTITUDE_TARGET: common.SetAttitudeTarget,
  ATTITUDE_TARGET: common.AttitudeTarget,
  HIGHRES_IMU: common.HighresImu,
  TIMESYNC: common.TimeSync,
  BATTERY_STATUS: common.BatteryStatus,
  EXTENDED_SYS_STATE: common.ExtendedSysState,
  STATUSTEXT: common.StatusText,
  HIL_SENSOR: common.HilSensor,
  HIL_ACTUATOR_CONTROLS: common.HilActuatorControls,
  HIL_STATE_QUATERNION: common.HilStateQuaternion,
  HIL_GPS: common.HilGps,
}

const BY_ID = {}
for (const [name, clazz] of Object.entries(MESSAGES)) BY_ID[clazz.MSG_ID] = { name, clazz }

function snake(name) {
  return name.replace(/^_/, '').replace(/[A-Z]/g, (c) => '_' + c.toLowerCase())
}

function jsonValue(value) {
  if (typeof value === 'bigint') return value.toString()
  if (Array.isArray(value)) return value.map(jsonValue)
  return value
}

function toJson(data) {
  const clazz = data.constructor
  const fields = {}
  for (const field of clazz.FIELDS) fields[snake(field.name)] = jsonValue(data[field.name])
  if (clazz === common.CommandLong) {
    fields.param = [1, 2, 3, 4, 5, 6, 7].map((i) => fields['param' + i])
    for (let i = 1; i <= 7; ++i) delete fields['param' + i]
  }
  return fields
}

// A message from field values given in the JSON naming (numbers for 64-bit fields too).
function fromJson(clazz, fields) {
  const data = new clazz()
  for (const field of clazz.FIELDS) {
    const key = snake(field.name)
    const isParam = clazz === common.CommandLong && /^param[1-7]$/.test(key)
    let value = isParam ? fields.param[Number(key.slice(5)) - 1] : fields[key]
    if (value === undefined) continue
    if (field.type.startsWith('int64_t') || field.type.startsWith('uint64_t')) {
      value = Array.isArray(value) ? value.map(BigInt) : BigInt(value)
    }
    data[field.name] = value
  }
  return data
}

module.exports = { MESSAGES, BY_ID, toJson, fromJson }
