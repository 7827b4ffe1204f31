// cover-bench ground-station: the operator's page on a standing realtime system
// (config/launch/system.yaml, --var clock=realtime: the simulator, both UGV agents, a UAV
// agent, the task manager), served by cover-ground-station and open in Debian's chromium
// (headless, driven by playwright-core: tests/ground_station/browser/bench_page.mjs). Over
// --seconds: each fleet row's draws per second on the page (the slowest row), Chromium's CPU
// for the page (its renderer and GPU processes, /proc/<pid>/stat), the station's CPU, and
// the latency from a status sample to its row drawn on the page, p50 / p99. The simulated
// fleet stamps its status with simulated time, so the latency is measured on a probe: this
// process publishes UAV 1's status at 10 Hz stamped with CLOCK_REALTIME (the page compares
// Date.now() with it, same host), and the station listens for UAVs 0..1. Each probe sample
// changes what its row shows (its process, 1/2 then 2/2): the station pushes such a row and
// the page draws it at its next frame, while a sample that only moves a row's age goes out
// with the next state (docs/ground-station.md), so the latency is of the samples the
// operator must see at once, every probe sample one of them (the worst case for the CPU). The
// station is started here rather than by the launch's ground_station: true, for a free port and its
// pid. Chromium composites the page in software, as it does without a usable GPU (this VM has
// none); --gpu-compositing measures SwiftShader compositing it instead (as the browser test
// runs): a GPU emulated on the CPU.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
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
#include "cover_binary.hpp"
#include "launch_run.hpp"
#include "not_measured.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using nlohmann::json;

const std::string kStation = cover::bench::cover_binary("cover-ground-station");
#ifdef COVER_BENCH_PAGE
const std::string kBenchPage = COVER_BENCH_PAGE;
#else
const std::string kBenchPage = "bench_page.mjs";
#endif
#ifdef COVER_WEB_DIR
const std::string kWebDir = COVER_WEB_DIR;
#else
const std::string kWebDir = "web";
#endif
const std::string kChromium = "/usr/bin/chromium";

// The probe's UAV id: one past the launched fleet's single UAV.
constexpr std::uint32_t kProbeUav = 1;
constexpr auto kProbePeriod = 100ms;

// The issue's targets (issue 33, "Done when").
constexpr double kTargetRowRateHz = 5.0;
constexpr double kTargetPageCpu = 0.10;
constexpr double kTargetServerCpu = 0.05;
constexpr double kTargetLatencyP99Ms = 50.0;

struct Figures {
  double seconds = NAN;
  double slowest_row_hz = NAN;
  std::string slowest_row;
  double page_cpu = NAN;  // of one core: renderer + GPU processes
  double renderer_cpu = NAN;
  double gpu_cpu = NAN;
  double server_cpu = NAN;
  double latency_p50_ms = NAN;
  double latency_p99_ms = NAN;
  std::size_t latency_samples = 0;
  double server_to_page_p50_ms = NAN;
  double server_to_page_p99_ms = NAN;
  double arrival_p50_ms = NAN;  // the sample's stamp to the message's arrival in the page
  double arrival_p99_ms = NAN;
  double states_hz = NAN;
  double pushes_hz = NAN;
  // The renderer's main thread, of one core (DevTools' Performance metrics): all of it, and
  // its script, style and layout shares; the rest of the renderer is its compositor and raster.
  double main_thread_cpu = NAN;
  double main_script_cpu = NAN;
  double main_style_layout_cpu = NAN;
  double frames_hz = NAN;         // style recalculations a second: the page's frames that changed
  double urgent_frames_hz = NAN;  // frames the page asked for at once, and within 150 ms
  double lazy_frames_hz = NAN;
};

// utime + stime of `pid`, seconds; NaN when it cannot be read.
double cpu_seconds(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  if (close == std::string::npos) return NAN;
  std::istringstream fields(text.substr(close + 2));
  std::string field;
  double ticks = 0.0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14 || i == 15) ticks += std::stod(field);
  }
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// node on $PATH, "" when none.
std::string find_node() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = dir + "/node";
    if (!dir.empty() && ::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

// What the page needs that is not there, each with how to get it.
std::vector<std::string> missing_browser_parts(const std::string& node) {
  std::vector<std::string> missing;
  if (node.empty()) missing.push_back("no node on PATH (scripts/setup installs Debian's nodejs)");
  if (!fs::exists(kChromium)) missing.push_back(kChromium + " missing (scripts/setup installs it)");
  if (!fs::exists(kWebDir + "/node_modules/playwright-core"))
    missing.push_back(kWebDir + "/node_modules/playwright-core missing (scripts/setup: npm ci)");
  if (!fs::exists(fs::path(kStation).parent_path() / "web/index.html"))
    missing.push_back("the page is not built (target ground_station_web)");
  return missing;
}

// UAV 1's status at 10 Hz stamped with CLOCK_REALTIME, until stopped.
class Probe {
 public:
  explicit Probe(int domain) {
    cover::dds::ParticipantOptions options;
    options.domain_id = domain;
    options.participant_name = "bench-ground-station-probe";
    participant_.emplace(options);
    writer_.emplace(participant_->make_writer(cover::dds::topics::uav_status(kProbeUav)));
    thread_ = std::thread([this] { run(); });
  }
  ~Probe() {
    stop_ = true;
    thread_.join();
  }

 private:
  void run() {
    auto next = std::chrono::steady_clock::now();
    for (std::uint32_t n = 0; !stop_; ++n) {
      cover::msg::UavStatus status;
      status.uav_id = kProbeUav;
      status.stamp_ns = cover::clock::system_ns();
      status.task_id = "probe";
      status.process_count = 2;
      status.process_index = n % 2;
      status.distance_to_stage_point_m = 0.001 * n;
      writer_->write(status);
      next += kProbePeriod;
      std::this_thread::sleep_until(next);  // the probe's own rate, not a synchronisation
    }
  }

  std::optional<cover::dds::Participant> participant_;
  std::optional<cover::dds::Writer<cover::msg::UavStatus>> writer_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// The page's report (bench_page.mjs) into the figures; `server_cpu_s` over the same window.
void read_page(const json& page, double server_cpu_s, Figures& f) {
  const double window = page.value("window_s", 0.0);
  if (window <= 0.0) return;
  f.seconds = window;
  for (const auto& [key, count] : page["row_updates"].items()) {
    const double hz = count.get<double>() / window;
    if (!(hz >= f.slowest_row_hz)) {
      f.slowest_row_hz = hz;
      f.slowest_row = key;
    }
  }
  if (page.value("renderers", 0) > 0) {
    f.renderer_cpu = page.value("renderer_cpu_s", NAN) / window;
    f.gpu_cpu = page.value("gpu_processes", 0) > 0 ? page.value("gpu_cpu_s", NAN) / window : 0.0;
    f.page_cpu = f.renderer_cpu + f.gpu_cpu;
  }
  f.server_cpu = server_cpu_s / window;
  const auto latencies = page["latencies_ms"].get<std::vector<double>>();
  f.latency_samples = latencies.size();
  f.latency_p50_ms = cover::bench::percentile(latencies, 0.50);
  f.latency_p99_ms = cover::bench::percentile(latencies, 0.99);
  const auto server = page["server_latencies_ms"].get<std::vector<double>>();
  f.server_to_page_p50_ms = cover::bench::percentile(server, 0.50);
  f.server_to_page_p99_ms = cover::bench::percentile(server, 0.99);
  const auto arrival = page.value("arrival_latencies_ms", std::vector<double>{});
  f.arrival_p50_ms = cover::bench::percentile(arrival, 0.50);
  f.arrival_p99_ms = cover::bench::percentile(arrival, 0.99);
  if (page.contains("main_thread") && page["main_thread"].is_object()) {
    const json& main = page["main_thread"];
    f.main_thread_cpu = main.value("ThreadTime", NAN) / window;
    f.main_script_cpu = main.value("ScriptDuration", NAN) / window;
    f.main_style_layout_cpu =
        (main.value("RecalcStyleDuration", NAN) + main.value("LayoutDuration", NAN)) / window;
    f.frames_hz = main.value("RecalcStyleCount", NAN) / window;
  }
  f.urgent_frames_hz = page.value("urgent_frames", NAN) / window;
  f.lazy_frames_hz = page.value("lazy_frames", NAN) / window;
  f.states_hz = page.value("states", 0) / window;
  f.pushes_hz = page.value("pushes", 0) / window;
}

// The station's address line ("ground station: open http://...") from its stdout.
std::string read_address(cover::process::ChildProcess& station) {
  while (const auto line = station.read_line(30s)) {
    std::smatch url;
    if (std::regex_search(*line, url, std::regex(R"(http://\S+)"))) return url.str();
  }
  return "";
}

// The page measured on the running station: the figures, or why not in `missing`.
Figures measure(const std::string& url, pid_t station_pid, double seconds, bool gpu_compositing,
                const std::string& node, const fs::path& dir, cover::bench::NotMeasured& missing) {
  Figures f;
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = (dir / "bench_page.log").string();
  options.extra_env = {"GS_URL=" + url,
                       "BENCH_SECONDS=" + std::to_string(seconds),
                       "CHROMIUM=" + kChromium,
                       "WEB_DIR=" + kWebDir,
                       "WAIT_ROWS=uav-agent/0 uav-agent/" + std::to_string(kProbeUav),
                       std::string("GPU_COMPOSITING=") + (gpu_compositing ? "1" : "0")};
  cover::process::ChildProcess page({node, kBenchPage}, options);
  double server_cpu0 = NAN;
  std::string failure = "the page script ended without a report";
  // Chromium's start, the page's first rows and the window: minutes on a loaded machine.
  const auto timeout = std::chrono::milliseconds(static_cast<long>(1000 * seconds)) + 300s;
  while (const auto line = page.read_line(timeout)) {
    if (*line == "measuring") {
      server_cpu0 = cpu_seconds(station_pid);
      continue;
    }
    const json report = json::parse(*line, nullptr, false);
    if (report.is_object()) {
      read_page(report, cpu_seconds(station_pid) - server_cpu0, f);
      break;
    }
    failure = *line;
  }
  // SIGTERM: playwright closes its browser before node exits.
  if (!page.wait(60s)) page.terminate(30s);
  if (!std::isfinite(f.seconds))
    missing.add("every figure: " + failure + " (" + options.log_file + ")");
  return f;
}

void name_missing(const Figures& f, cover::bench::NotMeasured& missing) {
  if (!std::isfinite(f.seconds)) return;  // already said why
  if (!std::isfinite(f.slowest_row_hz)) missing.add("row update rate: no fleet row drawn");
  if (!std::isfinite(f.page_cpu)) missing.add("Chromium's CPU: no renderer process found");
  if (!std::isfinite(f.server_cpu)) missing.add("the station's CPU: /proc unreadable");
  if (f.latency_samples == 0)
    missing.add("status -> page latency: no probe row with a wall-clock stamp drawn");
}

json figures_json(const Figures& f) {
  using cover::bench::figure_json;
  return {{"seconds", figure_json(f.seconds)},
          {"slowest_row_hz", figure_json(f.slowest_row_hz)},
          {"slowest_row", f.slowest_row},
          {"page_cpu_share", figure_json(f.page_cpu)},
          {"renderer_cpu_share", figure_json(f.renderer_cpu)},
          {"gpu_cpu_share", figure_json(f.gpu_cpu)},
          {"server_cpu_share", figure_json(f.server_cpu)},
          {"latency_p50_ms", figure_json(f.latency_p50_ms)},
          {"latency_p99_ms", figure_json(f.latency_p99_ms)},
          {"latency_samples", f.latency_samples},
          {"server_to_page_p50_ms", figure_json(f.server_to_page_p50_ms)},
          {"server_to_page_p99_ms", figure_json(f.server_to_page_p99_ms)},
          {"arrival_p50_ms", figure_json(f.arrival_p50_ms)},
          {"arrival_p99_ms", figure_json(f.arrival_p99_ms)},
          {"states_hz", figure_json(f.states_hz)},
          {"pushes_hz", figure_json(f.pushes_hz)},
          {"main_thread_cpu_share", figure_json(f.main_thread_cpu)},
          {"main_script_cpu_share", figure_json(f.main_script_cpu)},
          {"main_style_layout_cpu_share", figure_json(f.main_style_layout_cpu)},
          {"style_recalcs_hz", figure_json(f.frames_hz)},
          {"urgent_frames_hz", figure_json(f.urgent_frames_hz)},
          {"lazy_frames_hz", figure_json(f.lazy_frames_hz)}};
}

void print_table(const Figures& f) {
  using cover::bench::figure_text;
  const auto met = [](double v, bool ok) { return !std::isfinite(v) ? "-" : ok ? "yes" : "NO"; };
  std::printf("%-44s %14s %10s %6s\n", "figure", "measured", "target", "met");
  std::printf("%-44s %14s %10s %6s\n",
              ("fleet row draws, slowest row (" + f.slowest_row + ")").c_str(),
              figure_text("%.1f Hz", f.slowest_row_hz).c_str(), ">= 5 Hz",
              met(f.slowest_row_hz, f.slowest_row_hz >= kTargetRowRateHz));
  std::printf("%-44s %14s %10s %6s\n", "Chromium CPU for the page (renderer + GPU)",
              figure_text("%.1f %%", 100.0 * f.page_cpu).c_str(), "<= 10 %",
              met(f.page_cpu, f.page_cpu <= kTargetPageCpu));
  std::printf("%-44s %14s %10s %6s\n", "  of which renderer / GPU",
              (figure_text("%.1f", 100.0 * f.renderer_cpu) + " / " +
               figure_text("%.1f %%", 100.0 * f.gpu_cpu))
                  .c_str(),
              "", "");
  std::printf("%-44s %14s %10s %6s\n", "  renderer main thread: all / script / style+layout",
              (figure_text("%.1f", 100.0 * f.main_thread_cpu) + " / " +
               figure_text("%.1f", 100.0 * f.main_script_cpu) + " / " +
               figure_text("%.1f %%", 100.0 * f.main_style_layout_cpu))
                  .c_str(),
              "", "");
  std::printf("%-44s %14s %10s %6s\n", "  frames asked at once / within 150 ms / styled",
              (figure_text("%.1f", f.urgent_frames_hz) + " / " +
               figure_text("%.1f", f.lazy_frames_hz) + " / " + figure_text("%.1f /s", f.frames_hz))
                  .c_str(),
              "", "");
  std::printf("%-44s %14s %10s %6s\n", "station CPU",
              figure_text("%.1f %%", 100.0 * f.server_cpu).c_str(), "<= 5 %",
              met(f.server_cpu, f.server_cpu <= kTargetServerCpu));
  std::printf("%-44s %14s %10s %6s\n", "status sample -> page drawn, p50",
              figure_text("%.1f ms", f.latency_p50_ms).c_str(), "", "");
  std::printf("%-44s %14s %10s %6s\n", "status sample -> page drawn, p99",
              figure_text("%.1f ms", f.latency_p99_ms).c_str(), "<= 50 ms",
              met(f.latency_p99_ms, f.latency_p99_ms <= kTargetLatencyP99Ms));
  std::printf("%-44s %14s %10s %6s\n", "station receive -> page drawn, p50 / p99",
              (figure_text("%.1f", f.server_to_page_p50_ms) + " / " +
               figure_text("%.1f ms", f.server_to_page_p99_ms))
                  .c_str(),
              "", "");
  std::printf(
      "%-44s %14s %10s %6s\n", "status sample -> message in the page, p50 / p99",
      (figure_text("%.1f", f.arrival_p50_ms) + " / " + figure_text("%.1f ms", f.arrival_p99_ms))
          .c_str(),
      "", "");
  std::printf("(%s over %s: %zu probe samples; %s state and %s pushed messages a second)\n",
              "measured", figure_text("%.1f s", f.seconds).c_str(), f.latency_samples,
              figure_text("%.1f", f.states_hz).c_str(), figure_text("%.1f", f.pushes_hz).c_str());
}

int run(const std::vector<std::string>& args) {
  CLI::App app{
      "cover-bench ground-station: the operator's page on a standing realtime system in headless "
      "chromium: row update rate, Chromium's and the station's CPU, status -> page latency"};
  double seconds = 30.0;
  bool as_json = false;
  bool gpu_compositing = false;
  app.add_option("--seconds", seconds, "length of the measured window")
      ->check(CLI::Range(2.0, 3600.0))
      ->capture_default_str();
  app.add_flag("--gpu-compositing", gpu_compositing,
               "SwiftShader composites the page (as the browser test), not Chromium's software "
               "compositor");
  app.add_flag("--json", as_json, "one JSON object");
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;

  cover::bench::NotMeasured missing;
  const std::string node = find_node();
  for (const std::string& why : missing_browser_parts(node)) missing.add("every figure: " + why);
  Figures figures;
  if (missing.empty()) {
    const auto claim = cover::dds::DomainClaim::claim_any(150, 220);
    const fs::path dir =
        fs::temp_directory_path() / ("cover_bench_ground_station_" + std::to_string(getpid()));
    fs::create_directories(dir);
    cover::bench::LaunchRequest request;
    request.launch_file = cover::bench::launch_file_path("system");
    request.domain = claim.domain();
    request.run_dir = dir / "run";
    request.flags = {"--var", "clock=realtime", "--var", "db=" + (dir / "tasks.db").string()};
    cover::process::SpawnOptions launch_options;
    launch_options.log_file = (dir / "launch.log").string();
    cover::process::ChildProcess launch(cover::bench::launch_argv(request), launch_options);
    cover::process::SpawnOptions station_options;
    station_options.capture_stdout = true;
    station_options.log_file = (dir / "station.log").string();
    cover::process::ChildProcess station(
        {kStation, "--port", "0", "--uavs", std::to_string(kProbeUav + 1), "--ugvs", "2", "--dds",
         "fastdds", "--domain", std::to_string(claim.domain()), "--record-dir", dir.string()},
        station_options);
    const std::string url = read_address(station);
    if (url.empty()) {
      missing.add("every figure: the station printed no address (" + station_options.log_file +
                  ")");
    } else {
      Probe probe(claim.domain());
      figures = measure(url, station.pid(), seconds, gpu_compositing, node, dir, missing);
    }
    station.terminate(10s, SIGINT);
    launch.terminate(30s, SIGINT);
    name_missing(figures, missing);
    if (missing.empty())
      fs::remove_all(dir);
    else
      std::cerr << "cover-bench ground-station: logs kept in " << dir << "\n";
  }
  if (as_json) {
    json out = figures_json(figures);
    out["compositing"] = gpu_compositing ? "swiftshader" : "software";
    out["not_measured"] = missing.reasons();
    std::cout << out.dump(2) << std::endl;
  } else {
    std::printf("page composited by %s\n", gpu_compositing ? "SwiftShader (GPU emulated on the CPU)"
                                                           : "Chromium's software compositor");
    print_table(figures);
  }
  return missing.exit_code("ground-station");
}

const cover::bench::Registrar kRegistrar{
    "ground-station",
    "the operator's page in headless chromium on a standing realtime system: row update rate, "
    "Chromium's and the station's CPU, status -> page latency p50/p99",
    &run};

}  // namespace
