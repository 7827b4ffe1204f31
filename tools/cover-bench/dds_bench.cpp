// cover-bench dds: one-way latency of a RelativeState between two processes, for every
// vendor pair, back-to-back and paced at 100 Hz. One-way = round trip / 2, measured on
// one clock (the pinger's), so no clock synchronisation is involved.
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "dds_ping_pong.hpp"
#include "not_measured.hpp"

namespace {

using cover::dds::Vendor;
using cover::msg::RelativeState;

struct SeriesResult {
  int asked = 0;  // round trips asked for (0: the series was not asked for)
  int sent = 0;
  int received = 0;
  double p50_us = NAN;  // NaN: no round trip came back
  double p99_us = NAN;
};

// One-way = round trip / 2.
SeriesResult one_way(int asked, const cover::bench::RoundTrips& trips) {
  std::vector<double> one_way_us;
  one_way_us.reserve(trips.round_trip_us.size());
  for (const double round_trip : trips.round_trip_us) one_way_us.push_back(round_trip / 2.0);
  return {asked, trips.sent, trips.received, cover::bench::percentile(one_way_us, 0.50),
          cover::bench::percentile(one_way_us, 0.99)};
}

nlohmann::ordered_json to_json(const SeriesResult& r) {
  return {{"asked", r.asked},
          {"sent", r.sent},
          {"received", r.received},
          {"p50_us", cover::bench::figure_json(r.p50_us)},
          {"p99_us", cover::bench::figure_json(r.p99_us)}};
}

// A series asked for in which no round trip came back measured nothing.
void check(const SeriesResult& r, const std::string& what, cover::bench::NotMeasured& missing) {
  if (r.asked > 0 && r.received == 0) {
    missing.add(what + ": none of " + std::to_string(r.asked) + " round trips came back (" +
                std::to_string(r.sent) + " sent)");
  }
}

struct BenchOptions {
  int count = 2000;
  int paced_count = 300;
  int domain_id = 0;
  std::string prefix;
};

nlohmann::ordered_json run_pair(Vendor ping_vendor, Vendor pong_vendor, const BenchOptions& opts,
                                cover::bench::NotMeasured& missing) {
  cover::bench::PingPongOptions options;
  options.ping_vendor = ping_vendor;
  options.pong_vendor = pong_vendor;
  options.domain_id = opts.domain_id;
  options.prefix = opts.prefix;
  cover::bench::PingPong ping_pong(options);
  ping_pong.run(100, 0.0);  // warm-up: caches, first-time allocations
  const auto back_to_back = one_way(opts.count, ping_pong.run(opts.count, 0.0));
  const auto paced = one_way(opts.paced_count, ping_pong.run(opts.paced_count, 100.0));
  const std::string name = std::string(cover::dds::vendor_name(ping_vendor)) + "-" +
                           cover::dds::vendor_name(pong_vendor);
  check(back_to_back, name + " back-to-back", missing);
  check(paced, name + " paced at 100 Hz", missing);
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
      if (s["asked"].get<int>() == 0) return std::string("not asked");
      const auto us = [](const nlohmann::ordered_json& v) {
        return v.is_number() ? cover::bench::figure_text("%.1f us", v.get<double>())
                             : std::string("not measured");
      };
      return "p50 " + us(s["p50_us"]) + ", p99 " + us(s["p99_us"]) + ", " +
             std::to_string(s["received"].get<int>()) + "/" + std::to_string(s["sent"].get<int>());
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
  app.add_option("--count", opts.count, "Back-to-back round trips per pair (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--paced-count", opts.paced_count, "Round trips at 100 Hz per pair (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--domain", opts.domain_id, "DDS domain id (default: from the pid)");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;
  opts.prefix = "cover_bench/p" + std::to_string(getpid());
  cover::bench::NotMeasured missing;
  if (opts.count == 0 && opts.paced_count == 0) {
    missing.add("no round trip asked for (--count 0 --paced-count 0)");
    return missing.exit_code("dds");
  }

  nlohmann::ordered_json report;
  report["sample_type"] = RelativeState::kTypeName;
  report["qos"] = "reliable, volatile, keep-last 1";
  report["pairs"] = nlohmann::ordered_json::array();
  const std::pair<Vendor, Vendor> pairs[] = {{Vendor::FastDds, Vendor::FastDds},
                                             {Vendor::Cyclone, Vendor::Cyclone},
                                             {Vendor::FastDds, Vendor::Cyclone},
                                             {Vendor::Cyclone, Vendor::FastDds}};
  for (const auto& [ping, pong] : pairs) {
    report["pairs"].push_back(run_pair(ping, pong, opts, missing));
  }
  if (json) {
    std::cout << report.dump(2) << std::endl;
  } else {
    print_table(report);
  }
  return missing.exit_code("dds");
}

const cover::bench::Registrar dds_registrar{
    "dds", "DDS one-way latency, every vendor pair, back-to-back and at 100 Hz", &run_dds_bench};
const cover::bench::Registrar pong_registrar{"dds-pong", "(internal) echo peer of `dds` and `e2e`",
                                             &cover::bench::run_pong, /*handles_shutdown=*/true};

}  // namespace
