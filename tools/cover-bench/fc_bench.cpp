// cover-bench fc: the flight-controller path.
//  codec:   the MAVLink codec's cost per frame, encode and decode (stream parse, checksum,
//           signature check when signed, message unpack), for the setpoint the bridge sends
//           (SET_ATTITUDE_TARGET, 51-byte payload) and the IMU stream it reads (HIGHRES_IMU),
//           unsigned and signed. Target: a 51-byte frame decodes in <= 0.3 us (median).
//  latency: realtime Scenario 2 through cover-fc-bridge and the simulator's PX4 / ArduPilot:
//           a relative state's publication by the simulator -> the SET_ATTITUDE_TARGET
//           computed from it arriving at the simulated autopilot (one loopback UDP hop after
//           it left the bridge), as cover-sim measures it. Target: p50 <= 1 ms, p99 <= 2 ms.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "launch_run.hpp"
#include "not_measured.hpp"

namespace {

namespace mav = cover::mavlink;
using cover::bench::percentile;
using Clock = std::chrono::steady_clock;

constexpr double kDecodeTargetNs = 300.0;
constexpr double kLatencyP50TargetMs = 1.0;
constexpr double kLatencyP99TargetMs = 2.0;

mav::SigningKey bench_key() {
  mav::SigningKey key;
  for (std::size_t i = 0; i < key.secret.size(); ++i)
    key.secret[i] = static_cast<std::uint8_t>(i * 37 + 11);
  key.link_id = 1;
  return key;
}

mav::SetAttitudeTarget setpoint() {
  mav::SetAttitudeTarget m;
  m.time_boot_ms = 123456;
  m.q = {0.99F, 0.01F, -0.02F, 0.1F};
  m.body_roll_rate = 0.12F;
  m.body_pitch_rate = -0.34F;
  m.body_yaw_rate = 0.05F;
  m.thrust = 0.47F;
  m.target_system = 1;
  m.target_component = 1;
  m.type_mask = 128;
  m.thrust_body = {0.0F, 0.0F, -0.47F};  // non-zero last field: the full 51 bytes on the wire
  return m;
}

mav::HighresImu imu() {
  mav::HighresImu m;
  m.time_usec = 1234567890123ULL;
  m.xacc = 0.1F;
  m.yacc = -0.2F;
  m.zacc = -9.81F;
  m.xgyro = 0.01F;
  m.ygyro = -0.02F;
  m.zgyro = 0.03F;
  m.xmag = 0.2F;
  m.ymag = -0.1F;
  m.zmag = 0.45F;
  m.abs_pressure = 1013.25F;
  m.pressure_alt = 488.5F;
  m.temperature = 36.6F;
  m.fields_updated = 0x1FFF;
  m.id = 1;
  return m;
}

// One decoded field, summed so the decode cannot be optimised away.
float probe(const mav::SetAttitudeTarget& m) {
  return m.thrust;
}
float probe(const mav::HighresImu& m) {
  return m.zacc;
}

struct Row {
  std::string message;
  bool is_signed = false;
  std::size_t payload_bytes = 0;
  std::size_t frame_bytes = 0;
  std::vector<double> encode_ns;  // per frame, each sample the mean over one batch
  std::vector<double> decode_ns;
  std::uint64_t decoded = 0;
  std::uint64_t parser_errors = 0;
};

// Times `batch` calls of `op` per sample; returns ns per call for each sample.
template <typename Op>
std::vector<double> time_batches(int samples, int batch, Op&& op) {
  std::vector<double> ns;
  ns.reserve(static_cast<std::size_t>(samples));
  for (int s = 0; s < samples; ++s) {
    const auto t0 = Clock::now();
    for (int i = 0; i < batch; ++i) op();
    const auto t1 = Clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / batch);
  }
  return ns;
}

template <typename M>
Row measure(const char* name, const M& message, bool is_signed, int samples, int batch) {
  Row row;
  row.message = name;
  row.is_signed = is_signed;
  const std::optional<mav::SigningKey> key =
      is_signed ? std::optional<mav::SigningKey>(bench_key()) : std::nullopt;
  mav::Encoder encoder(1, 191, key);
  volatile std::size_t sink = 0;
  row.encode_ns = time_batches(samples, batch, [&] { sink = sink + encoder.encode(message).size; });

  // A ring of distinct frames (sequence numbers, signing timestamps) fed in order.
  std::vector<mav::EncodedFrame> frames(256);
  for (auto& f : frames) f = encoder.encode(message);
  row.frame_bytes = frames[0].size;
  row.payload_bytes = frames[0].bytes[1];
  mav::ParserOptions options;
  options.signing_key = key;
  options.require_signed = is_signed;
  mav::StreamParser parser(options);
  std::size_t next = 0;
  float checksum = 0.0F;
  const mav::StreamParser::FrameHandler handler = [&](const mav::Frame& frame) {
    const std::optional<M> m = mav::decode<M>(frame);
    row.decoded += m.has_value() ? 1 : 0;
    if (m) checksum += probe(*m);
  };
  row.decode_ns = time_batches(samples, batch, [&] {
    const mav::EncodedFrame& f = frames[next];
    next = (next + 1) % frames.size();
    parser.feed(f.bytes.data(), f.size, handler);
  });
  sink = sink + static_cast<std::size_t>(checksum != 0.0F);
  row.parser_errors = parser.stats().errors();
  return row;
}

nlohmann::json to_json(const Row& r) {
  return {{"message", r.message},
          {"signed", r.is_signed},
          {"payload_bytes", r.payload_bytes},
          {"frame_bytes", r.frame_bytes},
          {"encode_median_ns", percentile(r.encode_ns, 0.5)},
          {"encode_p99_ns", percentile(r.encode_ns, 0.99)},
          {"decode_median_ns", percentile(r.decode_ns, 0.5)},
          {"decode_p99_ns", percentile(r.decode_ns, 0.99)},
          {"frames_decoded", r.decoded},
          {"parser_errors", r.parser_errors}};
}

double number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

// One realtime Scenario 2 through the bridge and `autopilot`; its UDP ports moved per domain.
nlohmann::json latency_run(const std::string& autopilot, int domain) {
  const int base = 26000 + 8 * domain;
  std::vector<std::string> flags = {"--clock", "realtime"};
  const char* names[] = {"fc_port", "autopilot_port", "ugv0_imu_port", "ugv1_imu_port",
                         "ugv_autopilot_port"};
  for (int i = 0; i < 5; ++i) {
    flags.insert(flags.end(), {"--var", std::string(names[i]) + "=" + std::to_string(base + i)});
  }
  const nlohmann::json r = cover::bench::run_launch("scenario2_" + autopilot, flags, domain, "fc");
  const nlohmann::json latency =
      r.is_object() && r.contains("latency_ms") ? r["latency_ms"] : nlohmann::json::object();
  const int samples = latency.is_object() ? latency.value("samples", 0) : 0;
  return {{"autopilot", autopilot},
          {"domain", domain},
          {"reported", !r.empty()},
          {"success", r.is_object() && r.value("success", false)},
          {"landing_error_m", cover::bench::figure_json(number(r, "landing_error_m"))},
          {"p50_ms", cover::bench::figure_json(samples > 0 ? number(latency, "p50") : NAN)},
          {"p99_ms", cover::bench::figure_json(samples > 0 ? number(latency, "p99") : NAN)},
          {"samples", samples}};
}

// A latency run that reported no sample measured nothing, whether its mission flew or not.
void check_latency(const nlohmann::json& l, cover::bench::NotMeasured& missing) {
  if (l["samples"].get<int>() > 0) return;
  missing.add("latency through " + l["autopilot"].get<std::string>() + " (domain " +
              std::to_string(l["domain"].get<int>()) +
              "): the run reported no relative state -> setpoint sample (" +
              (!l["reported"].get<bool>() ? "the launch gave no result"
               : l["success"].get<bool>() ? "the mission succeeded"
                                          : "the mission failed") +
              ")");
}

int run(const std::vector<std::string>& args) {
  CLI::App app{
      "The flight-controller path. Codec: encode and decode time per frame (median, p99) for "
      "SET_ATTITUDE_TARGET and HIGHRES_IMU, unsigned and signed; each sample is the mean over "
      "--batch frames (one frame is too short for the clock); decode is the stream parser "
      "(checksum, signature check when signed) plus the message's unpack; target: the 51-byte "
      "setpoint decodes in <= 0.3 us median. Latency: realtime Scenario 2 through "
      "cover-fc-bridge and the simulator's autopilot, relative state published -> "
      "SET_ATTITUDE_TARGET received (p50 <= 1 ms, p99 <= 2 ms)."};
  bool json = false;
  int samples = 5000;
  int batch = 64;
  int runs = 4;
  int domain = 170;
  app.add_flag("--json", json, "print JSON");
  app.add_option("--samples", samples, "codec: timed samples per measurement")
      ->check(CLI::PositiveNumber);
  app.add_option("--batch", batch, "codec: frames per sample")->check(CLI::PositiveNumber);
  app.add_option("--runs", runs,
                 "latency: realtime Scenario 2 runs, PX4 and ArduPilot in turn (0: codec only)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--domain", domain, "latency: first DDS domain (one per run)")
      ->check(CLI::Range(0, 200))
      ->capture_default_str();
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  nlohmann::json latency = nlohmann::json::array();
  for (int i = 0; i < runs; ++i) {
    latency.push_back(latency_run(i % 2 == 0 ? "px4" : "ardupilot", domain + i));
    if (!json) std::fprintf(stderr, "fc latency run %d of %d done\n", i + 1, runs);
  }

  std::vector<Row> rows;
  for (bool is_signed : {false, true}) {
    rows.push_back(measure("SET_ATTITUDE_TARGET", setpoint(), is_signed, samples, batch));
    rows.push_back(measure("HIGHRES_IMU", imu(), is_signed, samples, batch));
  }
  const double setpoint_decode_ns = percentile(rows[0].decode_ns, 0.5);
  const bool target_met = setpoint_decode_ns <= kDecodeTargetNs;

  if (json) {
    nlohmann::json out;
    out["samples"] = samples;
    out["batch"] = batch;
    out["rows"] = nlohmann::json::array();
    for (const Row& r : rows) out["rows"].push_back(to_json(r));
    out["decode_target_ns"] = kDecodeTargetNs;
    out["decode_target_met"] = target_met;
    out["latency"] = latency;
    out["latency_target_ms"] = {{"p50", kLatencyP50TargetMs}, {"p99", kLatencyP99TargetMs}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("MAVLink codec, ns per frame (%d samples of %d frames)\n", samples, batch);
    std::printf("  %-20s %-8s %7s %7s %10s %10s %10s %10s\n", "message", "signed", "payload",
                "frame", "enc med", "enc p99", "dec med", "dec p99");
    for (const Row& r : rows) {
      std::printf("  %-20s %-8s %7zu %7zu %10.1f %10.1f %10.1f %10.1f\n", r.message.c_str(),
                  r.is_signed ? "yes" : "no", r.payload_bytes, r.frame_bytes,
                  percentile(r.encode_ns, 0.5), percentile(r.encode_ns, 0.99),
                  percentile(r.decode_ns, 0.5), percentile(r.decode_ns, 0.99));
    }
    std::printf("  decode of the 51-byte setpoint: %.1f ns median, target <= %.0f ns: %s\n",
                setpoint_decode_ns, kDecodeTargetNs, target_met ? "met" : "NOT met");
    if (!latency.empty()) {
      std::printf(
          "relative state published -> SET_ATTITUDE_TARGET at the autopilot, realtime Scenario 2 "
          "(target p50 <= %.0f ms, p99 <= %.0f ms)\n",
          kLatencyP50TargetMs, kLatencyP99TargetMs);
    }
    for (const auto& l : latency) {
      std::printf("  %-10s p50 %s  p99 %s  (%d samples), landing %s%s\n",
                  l["autopilot"].get<std::string>().c_str(),
                  cover::bench::figure_text("%.3f ms", number(l, "p50_ms")).c_str(),
                  cover::bench::figure_text("%.3f ms", number(l, "p99_ms")).c_str(),
                  l["samples"].get<int>(),
                  cover::bench::figure_text("%.3f m", number(l, "landing_error_m")).c_str(),
                  l["success"].get<bool>() ? "" : "  MISSION FAILED");
    }
  }
  cover::bench::NotMeasured missing;
  for (const auto& l : latency) check_latency(l, missing);
  int code = 0;
  for (const auto& l : latency) {
    if (!l["success"].get<bool>()) code = 1;
  }
  for (const Row& r : rows) {
    if (r.parser_errors != 0 || r.decoded == 0) {
      std::fprintf(stderr, "mavlink bench: %s frames were refused\n", r.message.c_str());
      code = 1;
    }
  }
  return missing.exit_code("fc", code);
}

const cover::bench::Registrar registrar{
    "fc",
    "flight-controller path: MAVLink codec ns per frame, relative state -> setpoint latency "
    "through the bridge",
    &run};

}  // namespace
