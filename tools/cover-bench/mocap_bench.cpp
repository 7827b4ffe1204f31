// cover-bench mocap: Scenario 2 flown through the motion-capture path (cover-launch
// config/launch/scenario2_mocap.yaml: cover-sim --mocap vrpn, cover-mocap-relay, the
// agents), the relay's relative states compared with the simulator's ground truth (its
// shared-memory world at each capture time): position and velocity error in G_k p50/p99,
// the fraction of valid samples, the latency the relay adds (its own measure: the frame's
// last message off the socket -> every pair written), the landing error; with the
// simulated mocap's noise and dropouts on (config/sim/mocap.yaml) and off, in lockstep and
// realtime. Issue 23's targets, without noise: position <= 5 mm and velocity <= 5 cm/s p99,
// relay latency <= 2 ms p99.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/clock/clock.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/shm/seqlock_reader.hpp"
#include "cover/sim/relative_sensor.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "cover_binary.hpp"
#include "launch_run.hpp"
#include "not_measured.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using cover::bench::percentile;
using cover::sim::SharedWorld;

struct Row {
  std::string clock;
  bool noise = true;
  bool success = false;
  double landing_error_m = NAN;
  double position_p50_m = NAN, position_p99_m = NAN;
  double velocity_p50_m_s = NAN, velocity_p99_m_s = NAN;
  // In flight: the UAV not resting on a surface, and not within kContactMargin of a
  // touchdown or lift-off (the velocity steps there; no filter follows a step).
  double flight_velocity_p99_m_s = NAN;
  double valid_fraction = NAN;
  std::size_t samples = 0, compared = 0;
  double relay_latency_p50_ms = NAN, relay_latency_p99_ms = NAN;
  std::size_t world_snapshots = 0;
  std::string world_error;  // why the simulator's world was not read, if it was not
};

std::string row_name(const Row& r) {
  return r.clock + (r.noise ? " noisy" : " clean");
}

// What a row did not measure, with why.
void check(const Row& r, cover::bench::NotMeasured& missing) {
  if (r.compared == 0) {
    missing.add(
        row_name(r) + ": no relative state compared with the truth (" + std::to_string(r.samples) +
        " received from the relay; the world: " +
        (r.world_error.empty() ? std::to_string(r.world_snapshots) + " snapshots" : r.world_error) +
        ")");
  }
  if (!std::isfinite(r.relay_latency_p99_ms)) {
    missing.add(row_name(r) + ": relay latency (mocap.log has no statistics line)");
  }
}

std::uint16_t free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(fd);
  return ntohs(a.sin_port);
}

// The world at every tick the bench saw, by simulated time (ns).
class WorldRecorder {
 public:
  // Reads the segment `name` from when it appears until stop().
  void start(const std::string& name) {
    thread_ = std::thread([this, name] {
      std::optional<cover::shm::SeqlockReader<SharedWorld>> reader;
      while (!reader && !stop_) {
        try {
          reader.emplace(cover::shm::SeqlockReader<SharedWorld>::open(
              name, cover::sim::kWorldSegmentLayoutVersion, 100ms));
        } catch (const std::exception& e) {
          std::lock_guard<std::mutex> lock(mutex_);
          error_ = e.what();  // the latest reason, reported if it never opens
        }
      }
      if (!reader) return;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        error_.clear();
      }
      SharedWorld world;
      while (!stop_) {
        std::int64_t stamp_ns = 0;
        if (reader->read(world, &stamp_ns)) {
          std::lock_guard<std::mutex> lock(mutex_);
          snapshots_.emplace(cover::clock::s_to_ns(world.time_s), world);
        }
        std::this_thread::sleep_for(50us);  // sampling the world, not a synchronisation
      }
    });
  }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  // Why the segment was not read ("" once it was).
  std::string error() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
  }
  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return snapshots_.size();
  }
  const SharedWorld* at(std::int64_t stamp_ns) const {
    const auto it = snapshots_.find(stamp_ns);
    return it == snapshots_.end() ? nullptr : &it->second;
  }
  // UAV `uav` resting on a surface in any snapshot within `margin_ns` of `stamp_ns`.
  bool near_contact(std::int64_t stamp_ns, std::uint32_t uav, std::int64_t margin_ns) const {
    for (auto it = snapshots_.lower_bound(stamp_ns - margin_ns);
         it != snapshots_.end() && it->first <= stamp_ns + margin_ns; ++it) {
      if (it->second.uavs[uav].contact.resting) return true;
    }
    return false;
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
  mutable std::mutex mutex_;
  std::string error_ = "not opened";
  std::map<std::int64_t, SharedWorld> snapshots_;
};

std::string noise_off_config(const fs::path& dir) {
  const fs::path file = dir / "mocap_no_noise.yaml";
  std::ofstream(file) << "mocap:\n  position_noise_m: 0.0\n  attitude_noise_rad: 0.0\n"
                      << "  dropout_probability: 0.0\n";
  return file.string();
}

// "relay latency p50 X ms p99 Y ms" of the relay's last statistics line.
void read_relay_latency(const fs::path& log, Row& row) {
  std::ifstream in(log);
  std::string line;
  static const std::regex pattern("relay latency p50 ([0-9.]+) ms p99 ([0-9.]+) ms");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_search(line, m, pattern)) {
      row.relay_latency_p50_ms = std::stod(m[1]);
      row.relay_latency_p99_ms = std::stod(m[2]);
    }
  }
}

void compare(const std::vector<cover::msg::RelativeState>& samples, const WorldRecorder& world,
             Row& row) {
  constexpr std::int64_t kContactMargin = 150'000'000;
  std::vector<double> position, velocity, flight_velocity;
  std::size_t valid = 0;
  for (const auto& s : samples) {
    ++row.samples;
    valid += s.valid;
    const SharedWorld* w = world.at(s.stamp_ns);
    if (!s.valid || !w) continue;
    const auto truth =
        cover::sim::true_relative_state(w->uavs[s.uav_id].state, w->ugvs[s.ugv_id], w->time_s);
    const auto& p = s.position_m;
    const auto& v = s.velocity_m_s;
    position.push_back((Eigen::Vector3d(p.x, p.y, p.z) - truth.position_m).norm());
    velocity.push_back((Eigen::Vector3d(v.x, v.y, v.z) - truth.velocity_m_s).norm());
    if (!world.near_contact(s.stamp_ns, s.uav_id, kContactMargin)) {
      flight_velocity.push_back(velocity.back());
    }
  }
  row.compared = position.size();
  row.valid_fraction = row.samples ? static_cast<double>(valid) / row.samples : NAN;
  row.position_p50_m = percentile(position, 0.5);
  row.position_p99_m = percentile(position, 0.99);
  row.velocity_p50_m_s = percentile(velocity, 0.5);
  row.velocity_p99_m_s = percentile(velocity, 0.99);
  row.flight_velocity_p99_m_s = percentile(flight_velocity, 0.99);
}

Row run_row(const std::string& clock, bool noise, const fs::path& dir) {
  Row row;
  row.clock = clock;
  row.noise = noise;
  const auto claim = cover::dds::DomainClaim::claim_any(132, 139);
  const fs::path run_dir = dir / (clock + (noise ? "_noise" : "_clean"));
  cover::dds::ParticipantOptions o;
  o.vendor = cover::dds::Vendor::FastDds;
  o.domain_id = claim.domain();
  cover::dds::Participant participant(o);
  std::mutex mutex;
  std::vector<cover::msg::RelativeState> samples;
  std::vector<cover::dds::Reader<cover::msg::RelativeState>> readers;
  for (std::uint32_t k = 0; k < 2; ++k) {
    readers.push_back(participant.make_reader(cover::dds::topics::relative_state(0, k),
                                              [&](const cover::msg::RelativeState& m) {
                                                std::lock_guard<std::mutex> lock(mutex);
                                                samples.push_back(m);
                                              }));
  }
  std::vector<std::string> argv{
      cover::bench::cover_binary("cover-launch"),
      (fs::path(cover::config::default_config_dir()) / "launch" / "scenario2_mocap.yaml").string(),
      "--domain",
      std::to_string(claim.domain()),
      "--run-dir",
      run_dir.string(),
      "--clock",
      clock,
      "--var",
      "mocap_port=" + std::to_string(free_tcp_port())};
  if (!noise) {
    argv.push_back("--var");
    argv.push_back("mocap_config=" + noise_off_config(dir));
  }
  cover::process::SpawnOptions spawn;
  spawn.log_file = (dir / (clock + (noise ? "_noise" : "_clean") + "_launch.log")).string();
  cover::process::ChildProcess launch(argv, spawn);
  // The simulator's segment, by the run id and domain the launch says it gave it.
  WorldRecorder world;
  if (const auto identity = cover::bench::wait_for_run_identity(run_dir, launch, 30s)) {
    world.start(cover::shm::segment_name((*identity)["domain"].get<int>(),
                                         (*identity)["run_id"].get<std::string>()));
  } else {
    row.world_error = "the launch wrote no " + (run_dir / "run.json").string();
  }
  const auto code = launch.wait(std::chrono::minutes(5));
  world.stop();
  if (row.world_error.empty()) row.world_error = world.error();
  row.world_snapshots = world.size();
  if (!code) launch.terminate(10s, SIGINT);
  std::ifstream result_file(run_dir / "result.json");
  if (result_file) {
    const auto result = nlohmann::json::parse(result_file, nullptr, false);
    if (result.is_object()) {
      row.success = result.value("success", false);
      row.landing_error_m = result.value("landing_error_m", NAN);
    }
  }
  read_relay_latency(run_dir / "mocap.log", row);
  std::lock_guard<std::mutex> lock(mutex);
  compare(samples, world, row);
  return row;
}

nlohmann::json to_json(const Row& r) {
  return {{"clock", r.clock},
          {"noise_and_dropouts", r.noise},
          {"success", r.success},
          {"landing_error_m", cover::bench::figure_json(r.landing_error_m)},
          {"position_error_p50_m", cover::bench::figure_json(r.position_p50_m)},
          {"position_error_p99_m", cover::bench::figure_json(r.position_p99_m)},
          {"velocity_error_p50_m_s", cover::bench::figure_json(r.velocity_p50_m_s)},
          {"velocity_error_p99_m_s", cover::bench::figure_json(r.velocity_p99_m_s)},
          {"flight_velocity_error_p99_m_s", cover::bench::figure_json(r.flight_velocity_p99_m_s)},
          {"valid_fraction", cover::bench::figure_json(r.valid_fraction)},
          {"samples", r.samples},
          {"compared", r.compared},
          {"world_snapshots", r.world_snapshots},
          {"relay_latency_p50_ms", cover::bench::figure_json(r.relay_latency_p50_ms)},
          {"relay_latency_p99_ms", cover::bench::figure_json(r.relay_latency_p99_ms)}};
}

void print(const Row& r) {
  using cover::bench::figure_text;
  const auto milli = [](const char* format, double value) {
    return figure_text(format, value * 1e3);
  };
  std::printf(
      "%-9s %-5s %-7s landing %s | position p50 %s p99 %s | velocity p50 %s p99 %s (in flight %s) "
      "| valid %s of %zu (%zu compared) | relay p50 %s p99 %s\n",
      r.clock.c_str(), r.noise ? "noisy" : "clean", r.success ? "success" : "FAILED",
      milli("%.1f mm", r.landing_error_m).c_str(), milli("%.2f mm", r.position_p50_m).c_str(),
      milli("%.2f mm", r.position_p99_m).c_str(), milli("%.1f mm/s", r.velocity_p50_m_s).c_str(),
      milli("%.1f mm/s", r.velocity_p99_m_s).c_str(),
      milli("%.1f mm/s", r.flight_velocity_p99_m_s).c_str(),
      figure_text("%.1f %%", r.valid_fraction * 100.0).c_str(), r.samples, r.compared,
      figure_text("%.3f ms", r.relay_latency_p50_ms).c_str(),
      figure_text("%.3f ms", r.relay_latency_p99_ms).c_str());
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"cover-bench mocap: Scenario 2 through cover-mocap-relay vs the simulator's truth"};
  bool json = false;
  std::vector<std::string> clocks{"lockstep", "realtime"};
  app.add_flag("--json", json, "one JSON object on stdout");
  app.add_option("--clock", clocks, "lockstep and/or realtime")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;
  // Under $TMPDIR (a test's scratch folder when a test runs it).
  std::string pattern = (fs::temp_directory_path() / "cover_bench_mocap_XXXXXX").string();
  const char* made = ::mkdtemp(pattern.data());
  if (made == nullptr) throw std::runtime_error("cannot create a folder " + pattern);
  const fs::path dir = made;
  std::vector<Row> rows;
  bool ok = true;
  cover::bench::NotMeasured missing;
  for (const auto& clock : clocks) {
    for (const bool noise : {false, true}) {
      rows.push_back(run_row(clock, noise, dir));
      if (!json) print(rows.back());
      ok = ok && rows.back().success;
      check(rows.back(), missing);
    }
  }
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& r : rows) out.push_back(to_json(r));
    std::cout << nlohmann::json{{"mocap", out}}.dump(2) << "\n";
  }
  if (ok && missing.empty()) {
    fs::remove_all(dir);
  } else {
    std::cerr << "mocap: " << (ok ? "a run measured nothing" : "a run failed")
              << "; its logs are in " << dir << "\n";
  }
  return missing.exit_code("mocap", ok ? 0 : 1);
}

const cover::bench::Registrar registrar{
    "mocap",
    "Scenario 2 through the VRPN mocap relay: relative-state errors vs truth, valid fraction, "
    "relay latency, noise and dropouts on/off",
    &run};

}  // namespace
