// The MAVLink codec on its own: checksum, message table, every message's layout and round
// trip, trimming and zero-fill, v1, signing, sequence gaps, and the stream parser's
// survival of hostile byte streams with every count checked exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "cover/mavlink/crc.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/hil_messages.hpp"
#include "cover/mavlink/message_table.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/signing.hpp"
#include "message_json.hpp"
#include "sample_messages.hpp"
#include "stream_builder.hpp"

namespace cover::mavlink {
namespace {

using test::append;
using test::Bytes;
using test::bytes_of;
using test::encode;
using test::sample_messages;
using test::test_key;
using test::to_json;
using test::v1_frame;

Bytes from_hex(const std::string& hex) {
  Bytes bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    bytes.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return bytes;
}

struct Parsed {
  std::vector<Frame> frames;
  ParserStats stats;
  std::size_t pending = 0;
};

// Feeds `stream` in pieces of `chunk` bytes (0: all at once).
Parsed parse(const Bytes& stream, const ParserOptions& options = {}, std::size_t chunk = 0) {
  Parsed out;
  StreamParser parser(options);
  const auto keep = [&out](const Frame& f) { out.frames.push_back(f); };
  const std::size_t step = chunk == 0 ? std::max<std::size_t>(stream.size(), 1) : chunk;
  for (std::size_t at = 0; at < stream.size(); at += step) {
    parser.feed(stream.data() + at, std::min(step, stream.size() - at), keep);
  }
  out.stats = parser.stats();
  out.pending = parser.pending_bytes();
  return out;
}

std::size_t wire_size(const Frame& f) {
  return (f.version == 2 ? kHeaderLengthV2 : kHeaderLengthV1) + f.payload_length + kChecksumLength +
         (f.is_signed() ? kSignatureLength : 0);
}

// Every byte is a delivered or skipped (unknown) frame's, a refused candidate's start
// marker, garbage or pending (valid when no delivered payload was truncated).
void expect_bytes_accounted(const Parsed& p, std::size_t fed) {
  std::size_t delivered = 0;
  for (const Frame& f : p.frames) delivered += wire_size(f);
  EXPECT_EQ(delivered + p.stats.unknown_frame_bytes + p.stats.refusals() + p.stats.garbage_bytes +
                p.pending,
            fed);
  EXPECT_EQ(p.stats.candidates, p.stats.frames + p.stats.unknown_frames + p.stats.refusals());
  EXPECT_EQ(p.stats.frames, p.frames.size());
}

const char* const kGoldenSetAttitudeTarget =
    "fd27000000ffbe520000e80300000000803f000000000000000000000000cdcccc3dcdcc4cbe9a99993e0000"
    "003f010180c0c7";

SetAttitudeTarget golden_setpoint() {
  SetAttitudeTarget m;
  m.time_boot_ms = 1000;
  m.q = {1.0F, 0.0F, 0.0F, 0.0F};
  m.body_roll_rate = 0.1F;
  m.body_pitch_rate = -0.2F;
  m.body_yaw_rate = 0.3F;
  m.thrust = 0.5F;
  m.target_system = 1;
  m.target_component = 1;
  m.type_mask = 128;
  return m;
}

// The bitwise definition (MAVLink's crc_accumulate in checksum.h), to check the table.
std::uint16_t reference_crc(std::uint8_t byte, std::uint16_t crc) {
  std::uint8_t tmp = static_cast<std::uint8_t>(byte ^ (crc & 0xFF));
  tmp = static_cast<std::uint8_t>(tmp ^ (tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

TEST(MavlinkCrc, CheckValueOfTheStandardVector) {
  const std::string text = "123456789";
  const auto* data = reinterpret_cast<const std::uint8_t*>(text.data());
  EXPECT_EQ(crc_accumulate(data, text.size(), kCrcInit), 0x6F91);
  EXPECT_EQ(crc_accumulate(data, 0, kCrcInit), kCrcInit);
}

TEST(MavlinkCrc, TableMatchesTheBitwiseDefinition) {
  std::mt19937 random(22);
  std::uint16_t table = kCrcInit;
  std::uint16_t bitwise = kCrcInit;
  for (int i = 0; i < 10000; ++i) {
    const auto byte = static_cast<std::uint8_t>(random());
    table = crc_accumulate(byte, table);
    bitwise = reference_crc(byte, bitwise);
    ASSERT_EQ(table, bitwise) << "after " << i + 1 << " bytes";
  }
}

template <typename M>
void expect_table_row(const M&) {
  const auto info = message_info(M::kId);
  ASSERT_TRUE(info.has_value()) << M::kId;
  EXPECT_EQ(info->crc_extra, M::kCrcExtra) << info->name;
  EXPECT_EQ(info->payload_length, M::kPayloadLength) << info->name;
}

TEST(MavlinkMessageTable, KnowsEveryMessageWithItsStructsConstants) {
  std::apply([](const auto&... m) { (expect_table_row(m), ...); }, sample_messages());
  // Streamed by autopilots, known without a struct (notes' table).
  EXPECT_EQ(message_info(2)->crc_extra, 137);  // SYSTEM_TIME
  EXPECT_EQ(message_info(2)->payload_length, 12);
  EXPECT_EQ(message_info(30)->crc_extra, 39);  // ATTITUDE
  EXPECT_EQ(message_info(30)->payload_length, 28);
  EXPECT_FALSE(message_info(3).has_value());
  EXPECT_FALSE(message_info(0xFFFFFF).has_value());
}

TEST(MavlinkGolden, SetAttitudeTargetEncodesByteForByte) {
  Encoder encoder(255, 190);
  EXPECT_EQ(bytes_of(encoder.encode(golden_setpoint())), from_hex(kGoldenSetAttitudeTarget));
}

TEST(MavlinkGolden, SetAttitudeTargetDecodes) {
  const Parsed p = parse(from_hex(kGoldenSetAttitudeTarget));
  ASSERT_EQ(p.frames.size(), 1U);
  const Frame& f = p.frames[0];
  EXPECT_EQ(f.version, 2);
  EXPECT_EQ(f.system_id, 255);
  EXPECT_EQ(f.component_id, 190);
  EXPECT_EQ(f.seq, 0);
  EXPECT_EQ(f.payload_length, 39);  // thrust_body's zeros trimmed
  EXPECT_EQ(to_json(*decode<SetAttitudeTarget>(f)), to_json(golden_setpoint()));
  EXPECT_FALSE(decode<AttitudeTarget>(f).has_value());
}

TEST(MavlinkMessages, PackWritesExactlyThePayloadLength) {
  std::apply(
      [](const auto&... m) {
        const auto check = [](const auto& message) {
          using M = std::decay_t<decltype(message)>;
          std::array<std::uint8_t, kMaxPayloadLength> buffer;
          buffer.fill(0xAA);
          message.pack(buffer.data());
          EXPECT_TRUE(std::all_of(buffer.begin() + M::kPayloadLength, buffer.end(),
                                  [](std::uint8_t b) { return b == 0xAA; }))
              << "message " << M::kId << " writes past its payload";
          EXPECT_NE(buffer[M::kPayloadLength - 1], 0xAA)
              << "message " << M::kId << " leaves its last byte unwritten";
        };
        (check(m), ...);
      },
      sample_messages());
}

TEST(MavlinkMessages, EveryMessageRoundTripsFieldByField) {
  Encoder encoder(42, 191);
  Bytes stream;
  std::apply([&](const auto&... m) { (append(stream, encode(encoder, m)), ...); },
             sample_messages());
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), std::tuple_size<test::AllMessages>::value);
  std::size_t i = 0;
  std::apply(
      [&](const auto&... m) {
        const auto check = [&](const auto& sent) {
          using M = std::decay_t<decltype(sent)>;
          const Frame& f = p.frames[i];
          EXPECT_EQ(f.seq, i);
          EXPECT_EQ(f.system_id, 42);
          EXPECT_EQ(f.component_id, 191);
          const std::optional<M> got = decode<M>(f);
          ASSERT_TRUE(got.has_value()) << "frame " << i;
          EXPECT_EQ(to_json(*got), to_json(sent)) << "message " << M::kId;
          ++i;
        };
        (check(m), ...);
      },
      sample_messages());
  EXPECT_EQ(p.stats.errors(), 0U);
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkMessages, StatusTextCutsAt50BytesAndReadsWithoutTerminator) {
  StatusText m;
  m.set_text(std::string(80, 'x'));
  EXPECT_EQ(m.text_string(), std::string(50, 'x'));
  m.set_text("short");
  EXPECT_EQ(m.text_string(), "short");
  EXPECT_EQ(m.text[5], '\0');
}

TEST(MavlinkTrimming, EncoderDropsTrailingZerosButKeepsOneByte) {
  Encoder encoder(1, 1);
  const EncodedFrame zeros = encoder.encode(ExtendedSysState{});
  EXPECT_EQ(zeros.bytes[1], 1);  // payload length on the wire
  EXPECT_EQ(zeros.size, kHeaderLengthV2 + 1 + kChecksumLength);
  const EncodedFrame ack = encoder.encode(CommandAck{});  // every field zero
  EXPECT_EQ(ack.bytes[1], 1);
  SetAttitudeTarget full = golden_setpoint();
  full.thrust_body = {0.0F, 0.0F, 1.0F};
  EXPECT_EQ(encoder.encode(full).bytes[1], SetAttitudeTarget::kPayloadLength);
}

TEST(MavlinkTrimming, TrimmedPayloadIsZeroFilledAndDecodes) {
  Encoder encoder(1, 1);
  CommandAck ack;
  ack.command = 400;
  ack.result = 4;  // extensions all zero: trimmed to 3 bytes
  const Parsed p = parse(encode(encoder, ack));
  ASSERT_EQ(p.frames.size(), 1U);
  EXPECT_EQ(p.frames[0].payload_length, 3);
  EXPECT_TRUE(std::all_of(p.frames[0].payload.begin() + 3, p.frames[0].payload.end(),
                          [](std::uint8_t b) { return b == 0; }));
  EXPECT_EQ(to_json(*decode<CommandAck>(p.frames[0])), to_json(ack));
}

TEST(MavlinkTrimming, LongerPayloadThanKnownIsTruncated) {
  // A newer sender's HEARTBEAT with 6 bytes of extensions we do not know.
  std::array<std::uint8_t, 15> payload{};
  std::get<Heartbeat>(sample_messages()).pack(payload.data());
  std::fill(payload.begin() + Heartbeat::kPayloadLength, payload.end(), 0x5A);
  Encoder encoder(1, 1);
  const Parsed p =
      parse(bytes_of(encoder.frame(Heartbeat::kId, Heartbeat::kCrcExtra, payload.data(), 15)));
  ASSERT_EQ(p.frames.size(), 1U);
  EXPECT_EQ(p.frames[0].payload_length, Heartbeat::kPayloadLength);
  EXPECT_EQ(p.frames[0].payload[Heartbeat::kPayloadLength], 0);
  EXPECT_EQ(to_json(*decode<Heartbeat>(p.frames[0])),
            to_json(std::get<Heartbeat>(sample_messages())));
}

TEST(MavlinkV1, FramesAreAcceptedAndDecoded) {
  const CommandLong command = std::get<CommandLong>(sample_messages());
  const Heartbeat heartbeat = std::get<Heartbeat>(sample_messages());
  Bytes stream = v1_frame(command, CommandLong::kPayloadLength, 7, 3, 4);
  append(stream, v1_frame(heartbeat, Heartbeat::kPayloadLength, 8, 3, 4));
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), 2U);
  EXPECT_EQ(p.frames[0].version, 1);
  EXPECT_EQ(p.frames[0].seq, 7);
  EXPECT_EQ(p.frames[0].system_id, 3);
  EXPECT_EQ(p.frames[0].component_id, 4);
  EXPECT_FALSE(p.frames[0].is_signed());
  EXPECT_EQ(to_json(*decode<CommandLong>(p.frames[0])), to_json(command));
  EXPECT_EQ(to_json(*decode<Heartbeat>(p.frames[1])), to_json(heartbeat));
  EXPECT_EQ(p.stats.sequence_gaps, 0U);
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkV1, ShortPayloadWithoutExtensionsIsZeroFilled) {
  // SYS_STATUS as a v1 sender writes it: 31 bytes, no extensions.
  const SysStatus status = std::get<SysStatus>(sample_messages());
  const Parsed p = parse(v1_frame(status, 31, 0, 1, 1));
  ASSERT_EQ(p.frames.size(), 1U);
  const SysStatus got = *decode<SysStatus>(p.frames[0]);
  EXPECT_EQ(got.battery_remaining, status.battery_remaining);
  EXPECT_EQ(got.onboard_control_sensors_present_extended, 0U);
}

TEST(MavlinkV1, OversizedLengthIsRefusedAndTheNextFrameFound) {
  const Heartbeat heartbeat = std::get<Heartbeat>(sample_messages());
  Bytes stream = v1_frame(heartbeat, Heartbeat::kPayloadLength + 1, 0, 1, 1);
  Encoder encoder(1, 1);
  const Bytes good = encode(encoder, heartbeat);
  append(stream, good);
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), 1U);
  EXPECT_EQ(p.frames[0].version, 2);
  EXPECT_EQ(p.stats.bad_length, 1U);
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkSigning, TimestampCountsTenMicrosecondsSince2015) {
  const std::int64_t epoch_us = 1420070400LL * 1000000LL;
  EXPECT_EQ(signing_timestamp(epoch_us), 0U);
  EXPECT_EQ(signing_timestamp(epoch_us + 25), 2U);
  EXPECT_EQ(signing_timestamp(epoch_us + 86400LL * 1000000LL), 8640000000ULL);
  EXPECT_EQ(signing_timestamp(0), 0U);  // before the epoch: clamped, never wraps
}

TEST(MavlinkSigning, SignedFramesVerifyWithTheKeyAndTimestampsIncrease) {
  Encoder encoder(42, 191, test_key(5));
  Bytes stream;
  const SetAttitudeTarget setpoint = std::get<SetAttitudeTarget>(sample_messages());
  for (int i = 0; i < 1000; ++i) append(stream, encode(encoder, setpoint));
  ParserOptions options;
  options.signing_key = test_key();
  options.require_signed = true;
  const Parsed p = parse(stream, options);
  ASSERT_EQ(p.frames.size(), 1000U);
  std::uint64_t last = 0;
  for (const Frame& f : p.frames) {
    EXPECT_TRUE(f.is_signed());
    EXPECT_EQ(f.signature[0], 5);  // link id
    std::uint64_t timestamp = 0;
    for (int b = 0; b < 6; ++b)
      timestamp |= static_cast<std::uint64_t>(f.signature[1 + b]) << (8 * b);
    EXPECT_GT(timestamp, last);
    last = timestamp;
  }
  EXPECT_EQ(to_json(*decode<SetAttitudeTarget>(p.frames.back())), to_json(setpoint));
  EXPECT_EQ(p.stats.errors(), 0U);
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkSigning, WrongKeyIsRefused) {
  Encoder encoder(1, 1, test_key());
  const Bytes frame = encode(encoder, std::get<Heartbeat>(sample_messages()));
  ParserOptions options;
  options.signing_key = test_key();
  options.signing_key->secret[31] ^= 1;
  const Parsed p = parse(frame, options);
  EXPECT_TRUE(p.frames.empty());
  EXPECT_EQ(p.stats.signature_errors, 1U);
  expect_bytes_accounted(p, frame.size());
}

TEST(MavlinkSigning, TamperedSignatureIsRefused) {
  Encoder encoder(1, 1, test_key());
  Bytes frame = encode(encoder, std::get<Heartbeat>(sample_messages()));
  frame.back() ^= 0x40;
  ParserOptions options;
  options.signing_key = test_key();
  const Parsed p = parse(frame, options);
  EXPECT_TRUE(p.frames.empty());
  EXPECT_EQ(p.stats.signature_errors, 1U);
}

TEST(MavlinkSigning, WithoutAKeySignedFramesPassUnchecked) {
  Encoder encoder(1, 1, test_key());
  Bytes frame = encode(encoder, std::get<Heartbeat>(sample_messages()));
  frame.back() ^= 0x40;  // not ours to judge without the key
  const Parsed p = parse(frame);
  ASSERT_EQ(p.frames.size(), 1U);
  EXPECT_TRUE(p.frames[0].is_signed());
}

TEST(MavlinkSigning, UnsignedFramesAreRefusedWhenSigningIsRequired) {
  Encoder plain(1, 1);
  const Heartbeat heartbeat = std::get<Heartbeat>(sample_messages());
  Bytes stream = encode(plain, heartbeat);
  append(stream, v1_frame(heartbeat, Heartbeat::kPayloadLength, 0, 2, 1));
  Encoder signer(1, 1, test_key());
  append(stream, encode(signer, heartbeat));
  ParserOptions options;
  options.signing_key = test_key();
  options.require_signed = true;
  const Parsed required = parse(stream, options);
  ASSERT_EQ(required.frames.size(), 1U);
  EXPECT_TRUE(required.frames[0].is_signed());
  EXPECT_EQ(required.stats.unsigned_refused, 2U);
  expect_bytes_accounted(required, stream.size());
  options.require_signed = false;
  EXPECT_EQ(parse(stream, options).frames.size(), 3U);
}

// A companion that learns its autopilot's system id re-addresses its encoder: its
// sequence runs on, so a receiver counting per sender sees no loss.
TEST(MavlinkSequence, ASenderReaddressedKeepsItsSequence) {
  Encoder encoder(1, 191);
  const ExtendedSysState state = std::get<ExtendedSysState>(sample_messages());
  Bytes stream;
  for (int i = 0; i < 3; ++i) append(stream, encode(encoder, state));
  encoder.set_sender(1, 191);
  for (int i = 0; i < 3; ++i) append(stream, encode(encoder, state));
  encoder.set_sender(7, 191);
  append(stream, encode(encoder, state));
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), 7U);
  EXPECT_EQ(p.stats.sequence_gaps, 0U);
  EXPECT_EQ(p.frames[6].system_id, 7);
  EXPECT_EQ(p.frames[6].seq, 6);
}

TEST(MavlinkSequence, GapsAreCountedPerSender) {
  Encoder a(1, 1);
  Encoder b(2, 1);
  const ExtendedSysState state = std::get<ExtendedSysState>(sample_messages());
  Bytes stream;
  for (int i = 0; i < 300; ++i) {  // a: 300 frames, wraps 255 -> 0 without a gap
    const Bytes frame = encode(a, state);
    if (i != 10 && i != 11 && i != 200) append(stream, frame);  // 3 lost
    append(stream, encode(b, state));                           // b interleaved, none lost
  }
  const Parsed p = parse(stream);
  EXPECT_EQ(p.frames.size(), 597U);
  EXPECT_EQ(p.stats.sequence_gaps, 3U);
  EXPECT_EQ(p.stats.errors(), 0U);
}

TEST(MavlinkSurvival, GarbageBetweenFramesIsCountedAndSkipped) {
  Encoder encoder(1, 1);
  std::mt19937 random(7);
  Bytes stream;
  std::size_t garbage = 0;
  for (int i = 0; i < 50; ++i) {
    const int n = static_cast<int>(random() % 40);
    for (int g = 0; g < n; ++g) {
      auto byte = static_cast<std::uint8_t>(random());
      if (byte == kMagicV1 || byte == kMagicV2) byte = 0x00;
      stream.push_back(byte);
    }
    garbage += static_cast<std::size_t>(n);
    append(stream, encode(encoder, std::get<HighresImu>(sample_messages())));
  }
  const Parsed p = parse(stream);
  EXPECT_EQ(p.frames.size(), 50U);
  EXPECT_EQ(p.stats.garbage_bytes, garbage);
  EXPECT_EQ(p.stats.sequence_gaps, 0U);
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkSurvival, WrongChecksumIsRefusedAndTheNextFrameFound) {
  Encoder encoder(1, 1);
  Bytes bad = encode(encoder, std::get<Heartbeat>(sample_messages()));
  bad[bad.size() - 1] ^= 0xFF;
  ASSERT_EQ(std::count(bad.begin() + 1, bad.end(), kMagicV2) +
                std::count(bad.begin() + 1, bad.end(), kMagicV1),
            0);
  Bytes stream = bad;
  append(stream, encode(encoder, std::get<Heartbeat>(sample_messages())));
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), 1U);
  EXPECT_EQ(p.frames[0].seq, 1);
  EXPECT_EQ(p.stats.crc_errors, 1U);
  EXPECT_EQ(p.stats.garbage_bytes, bad.size() - 1);  // all but the refused start marker
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkSurvival, UnknownIdIsCountedAndSkipped) {
  Encoder encoder(1, 1);
  const std::array<std::uint8_t, 4> payload{1, 2, 3, 4};
  Bytes stream = bytes_of(encoder.frame(9999, 0, payload.data(), payload.size()));
  append(stream, encode(encoder, std::get<Timesync>(sample_messages())));
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), 1U);
  EXPECT_EQ(p.frames[0].message_id, Timesync::kId);
  EXPECT_EQ(p.stats.unknown_frames, 1U);  // skipped whole: a start marker follows it
  EXPECT_EQ(p.stats.unknown_ids, 0U);
  EXPECT_EQ(p.stats.errors(), 0U);       // an unknown id is not an error: a richer dialect
  EXPECT_EQ(p.stats.sequence_gaps, 0U);  // its sequence number counts as received
  expect_bytes_accounted(p, stream.size());
}

// What real PX4 sends a companion: dozens of message types the codec does not know, whose
// payloads hold start-marker bytes. Skipped whole, they are neither errors nor losses
// (re-scanning their payloads found false frames: ~28 CRC errors/s, ~180 gaps/s).
TEST(MavlinkSurvival, AStreamOfUnknownTypesIsNeitherErrorsNorGaps) {
  Encoder encoder(1, 1);
  std::mt19937 random(7);
  Bytes stream;
  std::size_t known = 0;
  for (int i = 0; i < 500; ++i) {
    std::vector<std::uint8_t> payload(1 + random() % 200);
    for (auto& b : payload)
      b = (random() % 5 == 0) ? kMagicV2 : static_cast<std::uint8_t>(random());
    payload.back() = 1;  // not trimmed away by the encoder
    append(stream,
           bytes_of(encoder.frame(300 + random() % 100, 0, payload.data(), payload.size())));
    if (i % 10 == 0) {
      append(stream, encode(encoder, std::get<HighresImu>(sample_messages())));
      ++known;
    }
  }
  append(stream, encode(encoder, std::get<Heartbeat>(sample_messages())));
  ++known;
  for (std::size_t chunk : {1U, 13U, 280U, 4096U}) {
    const Parsed p = parse(stream, {}, chunk);
    EXPECT_EQ(p.frames.size(), known) << "chunk " << chunk;
    EXPECT_EQ(p.stats.unknown_frames, 500U) << "chunk " << chunk;
    EXPECT_EQ(p.stats.errors(), 0U) << "chunk " << chunk;
    EXPECT_EQ(p.stats.sequence_gaps, 0U) << "chunk " << chunk;
    expect_bytes_accounted(p, stream.size());
  }
}

// A false start marker whose "id" is unknown does not swallow the frames after it: its
// end must be a start marker, which a random span rarely is.
TEST(MavlinkSurvival, AnUnknownCandidateNotFollowedByAFrameIsRefused) {
  Encoder encoder(1, 1);
  Bytes stream{kMagicV2, 3, 0, 0, 0, 1, 1, 0x2C, 0x01, 0x00, 7, 7, 7, 0x12, 0x34, 0x00};
  append(stream, encode(encoder, std::get<Heartbeat>(sample_messages())));
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), 1U);
  EXPECT_EQ(p.frames[0].message_id, Heartbeat::kId);
  EXPECT_EQ(p.stats.unknown_ids, 1U);
  EXPECT_EQ(p.stats.unknown_frames, 0U);
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkSurvival, UnknownIncompatFlagIsRefused) {
  Encoder encoder(1, 1);
  Bytes frame = encode(encoder, std::get<Heartbeat>(sample_messages()));
  frame[2] = 0x02;
  const Parsed p = parse(frame);
  EXPECT_TRUE(p.frames.empty());
  EXPECT_EQ(p.stats.bad_length, 1U);
}

TEST(MavlinkSurvival, TruncatedFrameFollowedByAGoodOne) {
  Encoder encoder(1, 1);
  const Bytes cut = encode(encoder, std::get<HighresImu>(sample_messages()));
  Bytes stream(cut.begin(), cut.begin() + 30);  // the link dropped the rest
  const Bytes good = encode(encoder, std::get<AttitudeQuaternion>(sample_messages()));
  append(stream, good);
  append(stream, good);  // enough bytes for the cut frame's length to be reached
  const Parsed p = parse(stream);
  ASSERT_EQ(p.frames.size(), 2U);
  EXPECT_EQ(p.frames[0].message_id, AttitudeQuaternion::kId);
  EXPECT_EQ(p.stats.crc_errors, 1U);
  expect_bytes_accounted(p, stream.size());
}

TEST(MavlinkSurvival, FramesHiddenInsideAnOversizedCandidateAreFound) {
  // A v2 header claiming 255 bytes: every frame in its span is found once it is refused.
  Bytes stream{kMagicV2, 255, 0, 0, 0, 1, 1, 0, 0, 0};
  Encoder encoder(9, 9);
  for (int i = 0; i < 8; ++i)
    append(stream, encode(encoder, std::get<HighresImu>(sample_messages())));
  const Parsed p = parse(stream);
  EXPECT_EQ(p.frames.size(), 8U);
  EXPECT_EQ(p.stats.crc_errors, 1U);
  EXPECT_EQ(p.stats.sequence_gaps, 0U);
  expect_bytes_accounted(p, stream.size());
}

// A stream of every hazard at once, fed whole, byte by byte and in odd chunks.
Bytes hostile_stream() {
  Encoder encoder(1, 1);
  Encoder signer(2, 2, test_key());
  Bytes stream{0x00, 0x11, 0x22};                                           // 3 garbage
  append(stream, encode(encoder, std::get<Heartbeat>(sample_messages())));  // frame
  Bytes bad = encode(encoder, std::get<CommandAck>(sample_messages()));
  bad[12] ^= 1;  // crc error
  append(stream, bad);
  const std::array<std::uint8_t, 3> payload{9, 9, 9};
  append(stream, bytes_of(encoder.frame(600, 0, payload.data(), payload.size())));  // unknown
  append(stream, v1_frame(std::get<Heartbeat>(sample_messages()), 12, 0, 3, 3));    // bad length
  append(stream, encode(signer, std::get<StatusText>(sample_messages())));          // signed frame
  append(stream, v1_frame(std::get<CommandLong>(sample_messages()), 33, 0, 3, 3));  // v1 frame
  append(stream, encode(encoder, std::get<BatteryStatus>(sample_messages())));      // frame
  append(stream, Bytes{kMagicV2, 20, 0});  // pending at the end
  return stream;
}

TEST(MavlinkSurvival, StatsAreCountedExactlyInAnyChunking) {
  const Bytes stream = hostile_stream();
  const Parsed whole = parse(stream);
  EXPECT_EQ(whole.stats.frames, 4U);
  EXPECT_EQ(whole.stats.crc_errors, 1U);
  EXPECT_EQ(whole.stats.unknown_frames, 1U);
  EXPECT_EQ(whole.stats.unknown_ids, 0U);
  EXPECT_EQ(whole.stats.bad_length, 1U);
  EXPECT_EQ(whole.stats.signature_errors, 0U);
  EXPECT_EQ(whole.stats.unsigned_refused, 0U);
  EXPECT_EQ(whole.stats.sequence_gaps, 1U);  // sender (1,1): the crc error only
  EXPECT_EQ(whole.pending, 3U);
  expect_bytes_accounted(whole, stream.size());
  for (std::size_t chunk : {1U, 2U, 3U, 7U, 64U, 255U}) {
    const Parsed p = parse(stream, {}, chunk);
    ASSERT_EQ(p.frames.size(), whole.frames.size()) << "chunk " << chunk;
    for (std::size_t i = 0; i < p.frames.size(); ++i) {
      EXPECT_EQ(p.frames[i].message_id, whole.frames[i].message_id);
      EXPECT_EQ(p.frames[i].payload, whole.frames[i].payload);
    }
    EXPECT_EQ(p.stats.garbage_bytes, whole.stats.garbage_bytes) << "chunk " << chunk;
    EXPECT_EQ(p.stats.refusals(), whole.stats.refusals()) << "chunk " << chunk;
    EXPECT_EQ(p.stats.unknown_frames, whole.stats.unknown_frames) << "chunk " << chunk;
    EXPECT_EQ(p.stats.sequence_gaps, whole.stats.sequence_gaps) << "chunk " << chunk;
  }
}

TEST(MavlinkSurvival, RandomBytesNeverCrashAndAddUp) {
  std::mt19937 random(2022);
  for (int run = 0; run < 200; ++run) {
    Bytes stream(static_cast<std::size_t>(random() % 4096));
    for (auto& b : stream) {
      // Start markers often, so headers are tried.
      b = (random() % 8 == 0) ? kMagicV2 : static_cast<std::uint8_t>(random());
    }
    const Parsed p = parse(stream, {}, 1 + random() % 100);
    EXPECT_EQ(p.stats.candidates, p.stats.frames + p.stats.unknown_frames + p.stats.refusals());
    EXPECT_LE(p.stats.unknown_frame_bytes + p.stats.refusals() + p.stats.garbage_bytes + p.pending,
              stream.size());
  }
}

TEST(MavlinkSurvival, ResetForgetsAPartialFrameAsGarbage) {
  Encoder encoder(1, 1);
  const Bytes frame = encode(encoder, std::get<Heartbeat>(sample_messages()));
  StreamParser parser;
  int frames = 0;
  const auto count = [&frames](const Frame&) { ++frames; };
  parser.feed(frame.data(), 5, count);
  EXPECT_EQ(parser.pending_bytes(), 5U);
  parser.reset();
  EXPECT_EQ(parser.pending_bytes(), 0U);
  EXPECT_EQ(parser.stats().garbage_bytes, 5U);
  parser.feed(frame.data(), frame.size(), count);
  EXPECT_EQ(frames, 1);
}

}  // namespace
}  // namespace cover::mavlink

namespace cover::mavlink {
namespace {

// common.xml's order, which a hand-written codec easily gets wrong: time_usec, flags (u64)
// BEFORE controls (float[16]), then mode. PX4 fills HIL_ACTUATOR_CONTROLS this way.
TEST(MavlinkHil, ActuatorControlsWireOrderIsFlagsBeforeControls) {
  HilActuatorControls m;
  m.time_usec = 0x0102030405060708ULL;
  m.flags = 1;
  m.controls[0] = 1.0F;  // 0x3F800000
  m.mode = 129;
  std::array<std::uint8_t, kMaxPayloadLength> payload{};
  m.pack(payload.data());
  EXPECT_EQ(payload[0], 0x08);
  EXPECT_EQ(payload[7], 0x01);
  EXPECT_EQ(payload[8], 0x01);  // flags
  for (int i = 9; i < 16; ++i) EXPECT_EQ(payload[i], 0) << i;
  EXPECT_EQ(payload[16], 0x00);  // controls[0], little endian
  EXPECT_EQ(payload[18], 0x80);
  EXPECT_EQ(payload[19], 0x3F);
  EXPECT_EQ(payload[80], 129);  // mode
}

TEST(MavlinkHil, SensorFieldGroupsAreCommonXmlBits) {
  EXPECT_EQ(hil_sensor_fields::kImu, 63U);
  EXPECT_EQ(hil_sensor_fields::kImu | hil_sensor_fields::kMag, 511U);
  EXPECT_EQ(hil_sensor_fields::kBaro, 6656U);
  EXPECT_EQ(hil_sensor_fields::kImu | hil_sensor_fields::kMag | hil_sensor_fields::kBaro, 7167U);
}

}  // namespace
}  // namespace cover::mavlink
