// The MAVLink stream parser (cover_mavlink's StreamParser), fed any bytes from a serial
// port or a UDP socket, in any chunking, with and without a signing key.
// Contract: no crash; every delivered frame has a known id, a payload no longer than its
// message's and zero-filled past it, and decodes as its message; every candidate is
// delivered, skipped whole (an unknown id followed by a start marker) or refused exactly
// once, and every byte is accounted for (a delivered or skipped frame's, a refused
// candidate's start marker, garbage, or pending); feeding the same bytes in one
// call or in random chunks gives the same frames and the same counts.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "cover/mavlink/event_messages.hpp"
#include "cover/mavlink/hil_messages.hpp"
#include "cover/mavlink/message_table.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parameter_messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "fuzz_input.hpp"

namespace {

namespace mav = cover::mavlink;
using cover::fuzz::require;

// The tests' shared key (tests/mavlink/peer/test_key.js): seeds signed by node-mavlink
// verify with it.
mav::SigningKey test_key() {
  const char* const secret = "cover-mavlink-test-key-32-bytes!";
  mav::SigningKey key;
  std::memcpy(key.secret.data(), secret, key.secret.size());
  return key;
}

std::size_t wire_size(const mav::Frame& frame, std::uint8_t wire_payload_length) {
  const std::size_t header = frame.version == 2 ? mav::kHeaderLengthV2 : mav::kHeaderLengthV1;
  return header + wire_payload_length + mav::kChecksumLength +
         (frame.is_signed() ? mav::kSignatureLength : 0);
}

void decode_any(const mav::Frame& frame) {
  switch (frame.message_id) {
    case mav::Heartbeat::kId:
      require(mav::decode<mav::Heartbeat>(frame).has_value(), "heartbeat decodes");
      break;
    case mav::SysStatus::kId:
      require(mav::decode<mav::SysStatus>(frame).has_value(), "sys_status decodes");
      break;
    case mav::ScaledImu::kId:
      require(mav::decode<mav::ScaledImu>(frame).has_value(), "scaled_imu decodes");
      break;
    case mav::AttitudeQuaternion::kId:
      require(mav::decode<mav::AttitudeQuaternion>(frame).has_value(), "attitude_q decodes");
      break;
    case mav::CommandLong::kId:
      require(mav::decode<mav::CommandLong>(frame).has_value(), "command_long decodes");
      break;
    case mav::CommandAck::kId:
      require(mav::decode<mav::CommandAck>(frame).has_value(), "command_ack decodes");
      break;
    case mav::SetAttitudeTarget::kId:
      require(mav::decode<mav::SetAttitudeTarget>(frame).has_value(), "setpoint decodes");
      break;
    case mav::AttitudeTarget::kId:
      require(mav::decode<mav::AttitudeTarget>(frame).has_value(), "att_target decodes");
      break;
    case mav::HighresImu::kId:
      require(mav::decode<mav::HighresImu>(frame).has_value(), "highres_imu decodes");
      break;
    case mav::Timesync::kId:
      require(mav::decode<mav::Timesync>(frame).has_value(), "timesync decodes");
      break;
    case mav::BatteryStatus::kId:
      require(mav::decode<mav::BatteryStatus>(frame).has_value(), "battery decodes");
      break;
    case mav::ExtendedSysState::kId:
      require(mav::decode<mav::ExtendedSysState>(frame).has_value(), "ext_state decodes");
      break;
    case mav::StatusText::kId: {
      const auto text = mav::decode<mav::StatusText>(frame);
      require(text.has_value() && text->text_string().size() <= 50, "statustext decodes");
      break;
    }
    case mav::ParamValue::kId: {
      const auto value = mav::decode<mav::ParamValue>(frame);
      require(value.has_value() && mav::param_id_string(value->param_id).size() <= 16,
              "param_value decodes");
      break;
    }
    case mav::ParamRequestRead::kId:
      require(mav::decode<mav::ParamRequestRead>(frame).has_value(), "param_request decodes");
      break;
    case mav::ParamSet::kId:
      require(mav::decode<mav::ParamSet>(frame).has_value(), "param_set decodes");
      break;
    case mav::Event::kId:
      require(mav::decode<mav::Event>(frame).has_value(), "event decodes");
      break;
    case mav::CurrentEventSequence::kId:
      require(mav::decode<mav::CurrentEventSequence>(frame).has_value(), "event seq decodes");
      break;
    case mav::EstimatorStatus::kId:
      require(mav::decode<mav::EstimatorStatus>(frame).has_value(), "estimator decodes");
      break;
    case mav::EkfStatusReport::kId:
      require(mav::decode<mav::EkfStatusReport>(frame).has_value(), "ekf decodes");
      break;
    // PX4 SITL's simulator_mavlink answers (firmware_link::Px4HilLink reads them) and the
    // frames a simulator sends it.
    case mav::HilActuatorControls::kId:
      require(mav::decode<mav::HilActuatorControls>(frame).has_value(), "hil_actuators decodes");
      break;
    case mav::HilSensor::kId:
      require(mav::decode<mav::HilSensor>(frame).has_value(), "hil_sensor decodes");
      break;
    case mav::HilStateQuaternion::kId:
      require(mav::decode<mav::HilStateQuaternion>(frame).has_value(), "hil_state decodes");
      break;
    case mav::HilGps::kId:
      require(mav::decode<mav::HilGps>(frame).has_value(), "hil_gps decodes");
      break;
    case mav::LocalPositionNed::kId:
      require(mav::decode<mav::LocalPositionNed>(frame).has_value(), "local position decodes");
      break;
    default:
      break;  // known to the table (ATTITUDE, SYSTEM_TIME) without a struct
  }
  require(!mav::decode<mav::Heartbeat>(frame) || frame.message_id == mav::Heartbeat::kId,
          "decode<M> of another id is nullopt");
}

struct Run {
  std::vector<std::vector<std::uint8_t>> frames;  // header fields + payload, compared
  // A delivered frame's wire size is known exactly unless its payload filled its
  // message's: a v2 one may have been longer (newer extensions) and truncated.
  std::uint64_t delivered_bytes_min = 0;
  bool delivered_bytes_exact = true;
  mav::ParserStats stats;
  std::size_t pending = 0;
};

void check_frame(const mav::Frame& frame) {
  const auto info = mav::message_info(frame.message_id);
  require(info.has_value(), "delivered frame has a known id");
  require(frame.version == 1 || frame.version == 2, "version is 1 or 2");
  require(frame.payload_length <= info->payload_length, "payload no longer than known");
  require(std::all_of(frame.payload.begin() + frame.payload_length, frame.payload.end(),
                      [](std::uint8_t b) { return b == 0; }),
          "payload zero-filled past its length");
  decode_any(frame);
}

Run parse(const std::uint8_t* data, std::size_t size, const mav::ParserOptions& options,
          const std::vector<std::size_t>& chunks) {
  Run run;
  mav::StreamParser parser(options);
  const auto on_frame = [&run](const mav::Frame& frame) {
    check_frame(frame);
    // The wire length: the header's byte, which a longer-than-known payload exceeds.
    std::vector<std::uint8_t> record{frame.version,        frame.seq,
                                     frame.system_id,      frame.component_id,
                                     frame.payload_length, frame.incompat_flags};
    record.insert(record.end(), frame.payload.begin(), frame.payload.end());
    run.frames.push_back(record);
    run.delivered_bytes_min += wire_size(frame, frame.payload_length);
    const auto info = mav::message_info(frame.message_id);
    if (frame.version == 2 && frame.payload_length == info->payload_length) {
      run.delivered_bytes_exact = false;
    }
  };
  std::size_t at = 0;
  for (std::size_t chunk : chunks) {
    const std::size_t n = std::min(chunk, size - at);
    parser.feed(data + at, n, on_frame);
    at += n;
  }
  parser.feed(data + at, size - at, on_frame);
  run.stats = parser.stats();
  run.pending = parser.pending_bytes();
  return run;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::uint8_t mode = data[0];
  std::uint32_t chunk_seed = data[1];
  data += 2;
  size -= 2;

  mav::ParserOptions options;
  if ((mode & 1) != 0) options.signing_key = test_key();
  options.require_signed = (mode & 2) != 0;

  std::vector<std::size_t> chunks;
  for (std::size_t total = 0; total < size;) {
    chunk_seed = chunk_seed * 1103515245U + 12345U;
    const std::size_t chunk = 1 + (chunk_seed >> 16) % 97;
    chunks.push_back(chunk);
    total += chunk;
  }
  const Run whole = parse(data, size, options, {});
  const Run pieces = parse(data, size, options, chunks);

  const mav::ParserStats& s = whole.stats;
  require(s.candidates == s.frames + s.unknown_frames + s.refusals(),
          "each candidate delivered, skipped or refused once");
  require(s.frames == whole.frames.size(), "frames counted as delivered");
  const std::uint64_t accounted =
      s.unknown_frame_bytes + s.refusals() + s.garbage_bytes + whole.pending;
  require(accounted <= size, "no byte counted twice");
  if (whole.delivered_bytes_exact) {
    require(whole.delivered_bytes_min + accounted == size, "every byte accounted for");
  } else {
    require(whole.delivered_bytes_min + accounted <= size, "every byte accounted for");
  }
  require(whole.frames == pieces.frames, "chunking changes no frame");
  const mav::ParserStats& p = pieces.stats;
  require(p.frames == s.frames && p.garbage_bytes == s.garbage_bytes &&
              p.crc_errors == s.crc_errors && p.unknown_ids == s.unknown_ids &&
              p.unknown_frames == s.unknown_frames && p.bad_length == s.bad_length &&
              p.signature_errors == s.signature_errors &&
              p.unsigned_refused == s.unsigned_refused && p.sequence_gaps == s.sequence_gaps,
          "chunking changes no count");
  if (options.signing_key && options.require_signed) {
    for (const auto& record : whole.frames) {
      require((record[5] & mav::kIncompatSigned) != 0, "require_signed delivers signed only");
    }
  }
  return 0;
}
