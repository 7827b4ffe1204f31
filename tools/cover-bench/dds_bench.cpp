// cover-bench dds: one-way latency of a RelativeState between two processes, for every
// vendor pair, back-to-back and paced at 100 Hz. One-way = round trip / 2, measured on
// one clock (the pinger's), so no clock synchronisation is involved.
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/dds/participant.hpp"
#include "cover/process/child_process.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace {

using cover::dds::Vendor;
using cover::msg::RelativeState;
using namespace std::chrono_literals;

// Reliable so that a lost sample would be retransmitted rather than counted as lost;
// keep-last 1 because only one ping is in flight at a time.
cover::dds::Topic<RelativeState> bench_topic(const std::string& name) {
  return cover::dds::Topic<RelativeState>::uncatalogued(
      name, {"bench", cover::dds::Reliability::Reliable, cover::dds::Durability::Volatile, 1, 0.0});
}

struct SeriesResult {
  int sent = 0;
  int received = 0;
  double p50_us = 0;
  double p99_us = 0;
};

using cover::bench::percentile;

// Receives pongs and lets the pinger wait for a given sequence number.
class PongWaiter {
 public:
  void on_pong(const RelativeState& pong) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      last_seq_ = pong.stamp_ns;
    }
    arrived_.notify_all();
  }
  bool wait_for(std::int64_t seq, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return arrived_.wait_for(lock, timeout, [&] { return last_seq_ == seq; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::int64_t last_seq_ = -1;
};

SeriesResult run_series(cover::dds::Writer<RelativeState>& ping, PongWaiter& waiter,
                        std::int64_t& seq, int count, double rate_hz) {
  SeriesResult result;
  std::vector<double> one_way_us;
  one_way_us.reserve(static_cast<std::size_t>(count));
  RelativeState sample;
  sample.position_m = {1.0, 2.0, 3.0};
  sample.attitude = {1.0, 0.0, 0.0, 0.0};
  sample.valid = true;
  const auto period = rate_hz > 0 ? std::chrono::nanoseconds(static_cast<long>(1e9 / rate_hz))
                                  : std::chrono::nanoseconds(0);
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; i < count; ++i) {
    if (rate_hz > 0) {
      next += period;
      std::this_thread::sleep_until(next);
    }
    sample.stamp_ns = ++seq;
    const auto start = std::chrono::steady_clock::now();
    if (!ping.write(sample)) continue;
    ++result.sent;
    if (!waiter.wait_for(seq, 1000ms)) continue;  // counted as lost
    const auto round_trip = std::chrono::steady_clock::now() - start;
    ++result.received;
    one_way_us.push_back(std::chrono::duration<double, std::micro>(round_trip).count() / 2.0);
  }
  result.p50_us = percentile(one_way_us, 0.50);
  result.p99_us = percentile(one_way_us, 0.99);
  return result;
}

nlohmann::ordered_json to_json(const SeriesResult& r) {
  return {{"sent", r.sent}, {"received", r.received}, {"p50_us", r.p50_us}, {"p99_us", r.p99_us}};
}

struct BenchOptions {
  int count = 2000;
  int paced_count = 300;
  int domain_id = 0;
  std::string prefix;
};

nlohmann::ordered_json run_pair(Vendor ping_vendor, Vendor pong_vendor, const BenchOptions& opts) {
  cover::process::ChildProcess pong(
      {"/proc/self/exe", "dds-pong", "--dds", cover::dds::vendor_name(pong_vendor), "--domain",
       std::to_string(opts.domain_id), "--prefix", opts.prefix},
      {}, /*capture_stdout=*/true);
  const auto ready = pong.read_line(20s);
  if (!ready || *ready != "ready") throw std::runtime_error("the pong process did not start");

  cover::dds::ParticipantOptions options;
  options.vendor = ping_vendor;
  options.domain_id = opts.domain_id;
  options.participant_name = "cover-bench-ping";
  cover::dds::Participant participant(options);
  PongWaiter waiter;
  auto pong_reader = participant.make_reader(
      bench_topic(opts.prefix + "/pong"), [&waiter](const RelativeState& s) { waiter.on_pong(s); });
  auto ping = participant.make_writer(bench_topic(opts.prefix + "/ping"));
  if (!ping.wait_for_readers(1, 20s) || !pong_reader.wait_for_writers(1, 20s)) {
    throw std::runtime_error("ping and pong never matched");
  }
  std::int64_t seq = 0;
  run_series(ping, waiter, seq, 100, 0.0);  // warm-up: caches, first-time allocations
  const auto back_to_back = run_series(ping, waiter, seq, opts.count, 0.0);
  const auto paced = run_series(ping, waiter, seq, opts.paced_count, 100.0);
  pong.terminate();
  const std::string name = std::string(cover::dds::vendor_name(ping_vendor)) + "-" +
                           cover::dds::vendor_name(pong_vendor);
  return {{"pair", name},
          {"ping_vendor", cover::dds::vendor_name(ping_vendor)},
          {"pong_vendor", cover::dds::vendor_name(pong_vendor)},
          {"back_to_back", to_json(back_to_back)},
          {"paced_100hz", to_json(paced)}};
}

void print_table(const nlohmann::ordered_json& report) {
  std::cout << "One-way latency of a RelativeState between two processes (round trip / 2)\n\n"
            << std::left << std::setw(18) << "pair" << std::setw(36) << "back-to-back"
            << "paced 100 Hz\n";
  for (const auto& row : report["pairs"]) {
    auto cell = [](const nlohmann::ordered_json& s) {
      std::ostringstream text;
      text << std::fixed << std::setprecision(1) << "p50 " << s["p50_us"].get<double>()
           << " us, p99 " << s["p99_us"].get<double>() << " us, " << s["received"].get<int>() << "/"
           << s["sent"].get<int>();
      return text.str();
    };
    std::cout << std::setw(18) << row["pair"].get<std::string>() << std::setw(36)
              << cell(row["back_to_back"]) << cell(row["paced_100hz"]) << "\n";
  }
}

int run_dds_bench(const std::vector<std::string>& args) {
  CLI::App app{"cover-bench dds: ping-pong latency for every Fast DDS / Cyclone DDS pair"};
  bool json = false;
  BenchOptions opts;
  opts.domain_id = 1 + static_cast<int>(getpid() % 200);
  app.add_flag("--json", json, "Print JSON");
  app.add_option("--count", opts.count, "Back-to-back round trips per pair")->capture_default_str();
  app.add_option("--paced-count", opts.paced_count, "Round trips at 100 Hz per pair")
      ->capture_default_str();
  app.add_option("--domain", opts.domain_id, "DDS domain id (default: from the pid)");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;
  opts.prefix = "cover_bench/p" + std::to_string(getpid());

  nlohmann::ordered_json report;
  report["sample_type"] = RelativeState::kTypeName;
  report["qos"] = "reliable, volatile, keep-last 1";
  report["pairs"] = nlohmann::ordered_json::array();
  const std::pair<Vendor, Vendor> pairs[] = {{Vendor::FastDds, Vendor::FastDds},
                                             {Vendor::Cyclone, Vendor::Cyclone},
                                             {Vendor::FastDds, Vendor::Cyclone},
                                             {Vendor::Cyclone, Vendor::FastDds}};
  for (const auto& [ping, pong] : pairs) report["pairs"].push_back(run_pair(ping, pong, opts));
  if (json) {
    std::cout << report.dump(2) << std::endl;
  } else {
    print_table(report);
  }
  return 0;
}

// The echo side, run as a child process by run_dds_bench.
int run_dds_pong(const std::vector<std::string>& args) {
  cover::process::ShutdownSignal::install();
  CLI::App app{"cover-bench dds-pong: echo peer of `cover-bench dds` (internal)"};
  std::string vendor = "fastdds", prefix;
  int domain_id = 0;
  app.add_option("--dds", vendor);
  app.add_option("--domain", domain_id);
  app.add_option("--prefix", prefix)->required();
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;
  cover::dds::ParticipantOptions options;
  options.vendor = cover::dds::parse_vendor(vendor);
  options.domain_id = domain_id;
  options.participant_name = "cover-bench-pong";
  cover::dds::Participant participant(options);
  auto pong = participant.make_writer(bench_topic(prefix + "/pong"));
  auto ping = participant.make_reader(bench_topic(prefix + "/ping"),
                                      [&pong](const RelativeState& sample) { pong.write(sample); });
  std::cout << "ready" << std::endl;
  while (!cover::process::ShutdownSignal::wait_for(1000ms)) {
  }
  return 0;
}

const cover::bench::Registrar dds_registrar{
    "dds", "DDS one-way latency, every vendor pair, back-to-back and at 100 Hz", &run_dds_bench};
const cover::bench::Registrar pong_registrar{"dds-pong", "(internal) echo peer of `dds`",
                                             &run_dds_pong};

}  // namespace
