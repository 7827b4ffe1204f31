// The VRPN client session (cover_vrpn's ClientSession), fed any bytes a server or a
// desynchronised stream can send, whole and in random chunks.
// Contract: no crash; a delivered report names a tracked body; a valid one holds finite
// values and, for a pose, a unit quaternion; an invalid one holds zeros; once the session
// refuses the stream (foreign cookie, length out of bounds) it delivers nothing more;
// feeding the same bytes in one call or in random chunks gives the same reports and the
// same counts; what the session queues to send stays bounded.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "cover/vrpn/client_session.hpp"
#include "fuzz_input.hpp"

namespace {

namespace vrpn = cover::vrpn;
using cover::fuzz::require;

struct Run {
  std::vector<std::vector<double>> reports;
  vrpn::SessionStats stats;
  bool refused = false;
};

void check(const vrpn::TrackerReport& r, std::size_t bodies) {
  require(r.body >= 0 && static_cast<std::size_t>(r.body) < bodies, "report of a tracked body");
  if (!r.valid) {
    for (double v : r.position) require(v == 0.0, "a lost sample carries zeros");
    return;
  }
  for (double v : r.position) require(std::isfinite(v), "valid position is finite");
  double norm = 0.0;
  for (double v : r.quaternion_xyzw) {
    require(std::isfinite(v), "valid quaternion is finite");
    norm += v * v;
  }
  if (r.kind == vrpn::TrackerReport::Kind::Pose) {
    require(std::abs(std::sqrt(norm) - 1.0) < 1e-9, "pose quaternion is unit");
  }
}

Run parse(const std::uint8_t* data, std::size_t size, const std::vector<std::string>& bodies,
          std::size_t max_bytes, const std::vector<std::size_t>& chunks) {
  vrpn::SessionOptions options;
  options.bodies = bodies;
  options.max_message_bytes = max_bytes;
  options.max_remote_names = 16;
  vrpn::ClientSession session(options);
  session.start();
  Run run;
  const auto on_report = [&](const vrpn::TrackerReport& r) {
    require(!run.refused, "nothing delivered after a refusal");
    check(r, bodies.size());
    std::vector<double> record{static_cast<double>(r.body), static_cast<double>(r.sensor),
                               static_cast<double>(r.time.to_ns()), r.valid ? 1.0 : 0.0,
                               r.kind == vrpn::TrackerReport::Kind::Pose ? 1.0 : 0.0};
    record.insert(record.end(), r.position.begin(), r.position.end());
    record.insert(record.end(), r.quaternion_xyzw.begin(), r.quaternion_xyzw.end());
    run.reports.push_back(record);
  };
  std::size_t at = 0;
  auto feed = [&](std::size_t n) {
    const bool ok = session.feed(data + at, n, on_report);
    if (!ok) run.refused = true;
    require(ok || !session.error().empty(), "a refusal says why");
    at += n;
    // A pong is 24 bytes: what is queued is bounded by what came in, plus our descriptions.
    require(session.outgoing_bytes() <= 24 + 1024 + size, "outgoing bounded");
    session.consume_outgoing(session.outgoing_bytes());
  };
  for (std::size_t chunk : chunks) feed(std::min(chunk, size - at));
  feed(size - at);
  run.stats = session.stats();
  return run;
}

bool same(const vrpn::SessionStats& a, const vrpn::SessionStats& b) {
  return a.messages == b.messages && a.poses == b.poses && a.velocities == b.velocities &&
         a.lost_samples == b.lost_samples && a.wrong_size == b.wrong_size &&
         a.unknown_sender == b.unknown_sender && a.unknown_type == b.unknown_type &&
         a.untracked == b.untracked && a.bad_descriptions == b.bad_descriptions &&
         a.names_overflow == b.names_overflow && a.pings_answered == b.pings_answered &&
         a.bad_lengths == b.bad_lengths && a.bad_cookies == b.bad_cookies;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::uint8_t mode = data[0];
  std::uint32_t chunk_seed = data[1];
  data += 2;
  size -= 2;
  // The seeds' bodies, and a small message limit now and then.
  std::vector<std::string> bodies{"UAV_A", "Truck_2"};
  if (mode & 1) bodies.push_back("uav0");
  const std::size_t max_bytes = (mode & 2) ? 96 : 4096;

  std::vector<std::size_t> chunks;
  for (std::size_t total = 0; total < size;) {
    chunk_seed = chunk_seed * 1103515245U + 12345U;
    const std::size_t chunk = 1 + (chunk_seed >> 16) % 97;
    chunks.push_back(chunk);
    total += chunk;
  }
  const Run whole = parse(data, size, bodies, max_bytes, {});
  const Run pieces = parse(data, size, bodies, max_bytes, chunks);
  require(whole.reports == pieces.reports, "chunking changes no report");
  require(same(whole.stats, pieces.stats), "chunking changes no count");
  require(whole.refused == pieces.refused, "chunking changes no refusal");
  const auto& s = whole.stats;
  require(s.poses + s.velocities + s.lost_samples == whole.reports.size(),
          "every report counted once");
  require(s.bad_lengths + s.bad_cookies <= 1, "one refusal at most");
  return 0;
}
