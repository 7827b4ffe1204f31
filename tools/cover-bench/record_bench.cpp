// cover-bench record: the flight recorder (`cover record`, its own process) against a fleet
// of 4 UAVs and 4 UGVs published here at full rates (per UGV: IMU 200 Hz; per UAV: a
// relative state to each UGV 100 Hz, command and trace 100 Hz, status 10 Hz; the
// simulator's clock 100 Hz: 3340 samples/s), and at --scale times those rates: samples
// lost (published after the recorder heard every writer, missing from the file), samples
// per second written, file bytes per flight minute, and the recorder's CPU share of one
// core (utime + stime from /proc over the measured window), per compression; then the
// recorder's and the live view's CPU shares during a realtime Scenario 2 recorded and served
// by cover-launch --record --foxglove, a Foxglove client subscribed to every channel.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/clock/clock.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/foxglove/subscriber_client.hpp"
#include "cover/mcap/reader.hpp"
#include "cover/process/child_process.hpp"
#include "cover_binary.hpp"
#include "not_measured.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

const std::string kLauncher = cover::bench::cover_binary("cover-launch");
const std::string kCover = cover::bench::cover_binary("cover");

constexpr std::uint32_t kUavs = 4;
// cover-launch --foxglove serves the live view on the bridge's default port.
constexpr int kLiveViewPort = 8765;
constexpr std::uint32_t kUgvs = 4;

struct Row {
  std::string compression;
  double scale = 1.0;
  double duration_s = 0.0;
  std::uint64_t published = 0;
  std::uint64_t recorded = 0;
  double samples_per_s = 0.0;
  double bytes_per_minute = 0.0;
  double cpu_share = 0.0;  // of one core
};

// utime + stime of `pid`, in seconds.
double cpu_seconds(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  if (close == std::string::npos) return 0.0;
  std::istringstream fields(text.substr(close + 2));
  std::string field;
  double ticks = 0.0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14 || i == 15) ticks += std::stod(field);
  }
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// The fleet's writers, one per concrete topic.
class Fleet {
 public:
  explicit Fleet(cover::dds::Participant& p) {
    namespace topics = cover::dds::topics;
    for (std::uint32_t k = 0; k < kUgvs; ++k) imu_.push_back(p.make_writer(topics::ugv_imu(k)));
    for (std::uint32_t u = 0; u < kUavs; ++u) {
      for (std::uint32_t k = 0; k < kUgvs; ++k) {
        rel_.push_back(p.make_writer(topics::relative_state(u, k)));
      }
      cmd_.push_back(p.make_writer(topics::uav_command(u)));
      trace_.push_back(p.make_writer(topics::uav_trace(u)));
      status_.push_back(p.make_writer(topics::uav_status(u)));
    }
    clock_ = p.make_writer(topics::sim_clock());
  }

  bool wait_matched(std::chrono::milliseconds timeout) {
    bool ok = clock_.wait_for_readers(1, timeout);
    for (auto& w : imu_) ok = w.wait_for_readers(1, timeout) && ok;
    for (auto& w : rel_) ok = w.wait_for_readers(1, timeout) && ok;
    for (auto& w : cmd_) ok = w.wait_for_readers(1, timeout) && ok;
    for (auto& w : trace_) ok = w.wait_for_readers(1, timeout) && ok;
    for (auto& w : status_) ok = w.wait_for_readers(1, timeout) && ok;
    return ok;
  }

  // One 5 ms step (IMU every step, 100 Hz topics every 2nd, status every 20th); returns
  // the samples written.
  std::uint64_t step(std::uint64_t n, std::int64_t stamp_ns) {
    std::uint64_t written = 0;
    for (std::uint32_t k = 0; k < kUgvs; ++k) {
      cover::msg::UgvImu s;
      s.ugv_id = k;
      s.stamp_ns = stamp_ns;
      s.seq = static_cast<std::uint32_t>(n);
      s.specific_force_m_s2 = {0.01 * static_cast<double>(n % 100), 0.0, 9.81};
      written += imu_[k].write(s) ? 1 : 0;
    }
    if (n % 2 == 0) {
      for (std::uint32_t u = 0; u < kUavs; ++u) {
        for (std::uint32_t k = 0; k < kUgvs; ++k) {
          cover::msg::RelativeState s;
          s.uav_id = u;
          s.ugv_id = k;
          s.stamp_ns = stamp_ns;
          s.position_m = {1.0 * u, 2.0 * k, 0.001 * static_cast<double>(n % 1000)};
          s.attitude.w = 1.0;
          s.valid = true;
          written += rel_[u * kUgvs + k].write(s) ? 1 : 0;
        }
        cover::msg::UavCommand c;
        c.uav_id = u;
        c.stamp_ns = stamp_ns;
        c.seq = static_cast<std::uint32_t>(n / 2);
        c.thrust_m_s2 = 9.81;
        c.armed = true;
        written += cmd_[u].write(c) ? 1 : 0;
        cover::msg::ControlTrace t;
        t.uav_id = u;
        t.stamp_ns = stamp_ns;
        written += trace_[u].write(t) ? 1 : 0;
        if (n % 20 == 0) {
          cover::msg::UavStatus st;
          st.uav_id = u;
          st.stamp_ns = stamp_ns;
          st.task_id = "bench";
          written += status_[u].write(st) ? 1 : 0;
        }
      }
      cover::msg::SimClock tick;
      tick.stamp_ns = stamp_ns;
      tick.tick = n / 2;
      tick.period_s = 0.01;
      written += clock_.write(tick) ? 1 : 0;
    }
    return written;
  }

 private:
  std::vector<cover::dds::Writer<cover::msg::UgvImu>> imu_;
  std::vector<cover::dds::Writer<cover::msg::RelativeState>> rel_;
  std::vector<cover::dds::Writer<cover::msg::UavCommand>> cmd_;
  std::vector<cover::dds::Writer<cover::msg::ControlTrace>> trace_;
  std::vector<cover::dds::Writer<cover::msg::UavStatus>> status_;
  cover::dds::Writer<cover::msg::SimClock> clock_;
};

// Messages in `file` stamped at or after `from_ns`.
std::uint64_t recorded_since(const std::string& file, std::int64_t from_ns) {
  std::uint64_t count = 0;
  cover::mcap::Reader reader(file);
  reader.scan([&](const cover::mcap::MessageView& m) {
    if (static_cast<std::int64_t>(m.header.publish_time_ns) >= from_ns) ++count;
    return true;
  });
  return count;
}

Row run_row(const std::string& compression, double scale, double duration_s, int domain,
            const fs::path& dir) {
  Row row;
  row.compression = compression;
  row.scale = scale;
  const std::string file = (dir / ("record_" + compression + ".mcap")).string();
  cover::process::SpawnOptions options;
  options.log_file = (dir / ("record_" + compression + ".log")).string();
  cover::process::ChildProcess recorder(
      {kCover, "record", "-o", file, "--compression", compression, "--uavs", "4", "--ugvs", "4",
       "--dds", "fastdds", "--domain", std::to_string(domain)},
      options);
  cover::dds::ParticipantOptions participant_options;
  participant_options.domain_id = domain;
  participant_options.participant_name = "bench-fleet";
  cover::dds::Participant participant(participant_options);
  Fleet fleet(participant);
  if (!fleet.wait_matched(20s)) std::cerr << "record: the recorder did not match every writer\n";

  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(0.005 / scale));
  auto next = Clock::now();
  std::uint64_t n = 0;
  // Warm-up (1 s): the recorder's readers learn every writer (a reliable sample written
  // before that is not delivered); left out of the count.
  for (const auto warm_end = Clock::now() + 1s; Clock::now() < warm_end; ++n) {
    fleet.step(n, 1 + static_cast<std::int64_t>(n));
    next += period;
    std::this_thread::sleep_until(next);
  }
  const std::int64_t measured_from_ns = 1'000'000'000'000;
  const double cpu_before = cpu_seconds(recorder.pid());
  const auto start = Clock::now();
  const auto end = start + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(duration_s));
  next = start;
  for (; Clock::now() < end; ++n) {
    row.published += fleet.step(n, measured_from_ns + static_cast<std::int64_t>(n) * 5'000'000);
    next += period;
    std::this_thread::sleep_until(next);
  }
  row.duration_s = std::chrono::duration<double>(Clock::now() - start).count();
  // Let the recorder write what is in flight, then stop it (it drains and closes).
  std::this_thread::sleep_for(300ms);
  row.cpu_share = (cpu_seconds(recorder.pid()) - cpu_before) / row.duration_s;
  recorder.terminate(10s, SIGINT);
  row.recorded = recorded_since(file, measured_from_ns);
  row.samples_per_s = static_cast<double>(row.recorded) / row.duration_s;
  row.bytes_per_minute = static_cast<double>(fs::file_size(file)) / (row.duration_s + 1.0) * 60.0;
  return row;
}

// `label ... s: X` in a process's log (its CPU share, in percent, logged at exit) as a
// fraction of one core; negative when the line is missing.
double logged_cpu_share(const fs::path& log_path, const std::string& label) {
  std::ifstream log(log_path);
  std::string line;
  double share = -1.0;
  while (std::getline(log, line)) {
    const auto at = line.find(" s: ");
    if (line.find(label) != std::string::npos && at != std::string::npos) {
      share = std::stod(line.substr(at + 4)) / 100.0;
    }
  }
  return share;
}

struct Scenario2Shares {
  double recorder = -1.0;  // of one core; negative when the run failed
  double live_view = -1.0;
  std::uint64_t live_view_messages = 0;  // what the subscribed-to-everything client received
  std::uint64_t live_view_channels = 0;
};

// The launch's recorder and live view during a realtime Scenario 2 (cover-launch --record
// --foxglove), a Foxglove client subscribed to every advertised channel: their CPU shares
// of one core as they log them at exit.
Scenario2Shares scenario2_cpu_shares(int domain, const fs::path& dir) {
  const fs::path run_dir = dir / "scenario2";
  cover::process::SpawnOptions options;
  options.log_file = (dir / "launch.log").string();
  cover::foxglove::SubscriberClient client("ws://127.0.0.1:" + std::to_string(kLiveViewPort));
  cover::process::ChildProcess launch(
      {kLauncher, cover::config::default_config_dir() + "/launch/scenario2.yaml", "--clock",
       "realtime", "--record", "--foxglove", "--domain", std::to_string(domain), "--run-dir",
       run_dir.string()},
      options);
  Scenario2Shares shares;
  const bool ok = launch.wait(120s).value_or(-1) == 0;
  const auto counts = client.counts();
  client.stop();
  if (!ok) return shares;
  shares.recorder = logged_cpu_share(run_dir / "recorder.log", "recorder CPU");
  shares.live_view = logged_cpu_share(run_dir / "foxglove.log", "bridge CPU");
  shares.live_view_messages = counts.messages;
  shares.live_view_channels = counts.channels_advertised;
  return shares;
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"cover-bench record: the flight recorder against a 4-UAV, 4-UGV fleet"};
  double duration_s = 10.0;
  std::vector<double> scales{1.0, 10.0};
  bool json = false;
  app.add_option("--duration", duration_s, "seconds measured per row")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--scale", scales, "rate factors of the fleet (1: full rates)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--json", json, "one JSON object");
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;

  const auto claim = cover::dds::DomainClaim::claim_any(195, 199);
  const fs::path dir =
      fs::temp_directory_path() / ("cover_bench_record_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::vector<Row> rows;
  for (const double scale : scales) {
    for (const std::string compression : {"zstd", "lz4", "none"}) {
      if (scale != 1.0 && compression != "zstd") continue;
      rows.push_back(run_row(compression, scale, duration_s, claim.domain(), dir));
    }
  }
  const Scenario2Shares scenario2 = scenario2_cpu_shares(claim.domain(), dir);
  fs::remove_all(dir);
  cover::bench::NotMeasured missing;
  for (const auto& r : rows) {
    if (r.recorded == 0) {
      missing.add("record " + r.compression + " at " + std::to_string(r.scale) +
                  "x: the recorder wrote no sample of the " + std::to_string(r.published) +
                  " published");
    }
  }
  if (scenario2.recorder < 0.0) {
    missing.add(
        "the recorder's share in realtime Scenario 2: the run failed or its recorder "
        "logged no CPU line");
  }
  if (scenario2.live_view < 0.0) {
    missing.add(
        "the live view's share in realtime Scenario 2: the run failed or the bridge "
        "logged no CPU line");
  }
  // A share as a fraction of one core, or not measured (negative: the run gave none).
  const auto share = [](double fraction) { return fraction >= 0.0 ? fraction : NAN; };

  nlohmann::json out = nlohmann::json::array();
  for (const auto& r : rows) {
    out.push_back(
        {{"compression", r.compression},
         {"rate_scale", r.scale},
         {"duration_s", r.duration_s},
         {"published", r.published},
         {"recorded", r.recorded},
         {"lost", r.published - std::min(r.published, r.recorded)},
         {"samples_per_s", cover::bench::figure_json(r.recorded ? r.samples_per_s : NAN)},
         {"bytes_per_flight_minute",
          cover::bench::figure_json(r.recorded ? r.bytes_per_minute : NAN)},
         {"cpu_share_of_one_core", cover::bench::figure_json(r.recorded ? r.cpu_share : NAN)}});
  }
  if (json) {
    std::cout << nlohmann::json{{"record", out},
                                {"scenario2_realtime_recorder_cpu_share",
                                 cover::bench::figure_json(share(scenario2.recorder))},
                                {"scenario2_realtime_live_view_cpu_share",
                                 cover::bench::figure_json(share(scenario2.live_view))},
                                {"scenario2_live_view_messages", scenario2.live_view_messages},
                                {"scenario2_live_view_channels", scenario2.live_view_channels}}
                     .dump()
              << std::endl;
    return missing.exit_code("record");
  }
  std::printf("%-6s %6s %10s %10s %6s %10s %14s %8s\n", "compr", "scale", "published", "recorded",
              "lost", "samples/s", "MiB/flight-min", "CPU");
  for (const auto& r : rows) {
    // A recorder that wrote nothing measured no rate, size or share.
    const double measured = r.recorded > 0 ? 1.0 : NAN;
    std::printf(
        "%-6s %6.0f %10llu %10llu %6llu %10s %14s %8s\n", r.compression.c_str(), r.scale,
        static_cast<unsigned long long>(r.published), static_cast<unsigned long long>(r.recorded),
        static_cast<unsigned long long>(r.published - std::min(r.published, r.recorded)),
        cover::bench::figure_text("%.0f", measured * r.samples_per_s).c_str(),
        cover::bench::figure_text("%.2f", measured * r.bytes_per_minute / 1048576.0).c_str(),
        cover::bench::figure_text("%.1f%%", measured * 100.0 * r.cpu_share).c_str());
  }
  std::printf(
      "realtime Scenario 2 (cover-launch --record --foxglove): recorder %s, live view %s "
      "of one core (its client subscribed to %llu channels, received %llu messages)\n",
      cover::bench::figure_text("%.1f %%", 100.0 * share(scenario2.recorder)).c_str(),
      cover::bench::figure_text("%.1f %%", 100.0 * share(scenario2.live_view)).c_str(),
      static_cast<unsigned long long>(scenario2.live_view_channels),
      static_cast<unsigned long long>(scenario2.live_view_messages));
  return missing.exit_code("record");
}

const cover::bench::Registrar registrar{
    "record",
    "flight recorder: samples lost and per second, bytes per flight minute per compression, CPU "
    "share, against a 4-UAV 4-UGV fleet at full (and --scale) rates",
    &run};

}  // namespace
