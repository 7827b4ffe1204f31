#include "cover/launch/run_report.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace cover::launch {
namespace {

// The ends_run process's own result, when it wrote one that is a JSON object.
nlohmann::json read_result(const std::string& run_dir) {
  std::ifstream stream(std::filesystem::path(run_dir) / "result.json");
  if (stream) {
    const auto result = nlohmann::json::parse(stream, nullptr, /*allow_exceptions=*/false);
    if (result.is_object()) return result;
  }
  return {{"result_missing", true}};
}

nlohmann::json optional_number(const std::optional<int>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json make_report(const LaunchPlan& plan, const RunOutcome& outcome) {
  nlohmann::json report = read_result(plan.run_dir);
  nlohmann::json processes = nlohmann::json::array();
  for (const auto& process : outcome.processes) {
    processes.push_back(
        {{"name", process.name},
         {"dds", process.dds},
         {"pid", optional_number(process.pid)},
         {"exit_code", optional_number(process.exit_code)},
         {"stopped_by", process.stopped_by},
         {"respawns", process.respawns},
         {"realtime_priority", process.realtime_priority},
         {"cpus", process.cpus},
         {"cpu_s", process.cpu_s ? nlohmann::json(*process.cpu_s) : nlohmann::json(nullptr)},
         {"max_rss_kib",
          process.max_rss_kib ? nlohmann::json(*process.max_rss_kib) : nlohmann::json(nullptr)}});
  }
  report["processes"] = std::move(processes);
  report["variables"] = plan.variables;
  report["run_dir"] = plan.run_dir;
  report["run_id"] = plan.run_id;
  report["leftover_segments"] = outcome.leftover_segments;
  report["exit_code"] = outcome.exit_code;
  return report;
}

nlohmann::json make_identity(const LaunchPlan& plan, int launcher_pid) {
  return {{"name", plan.name},        {"kind", to_string(plan.kind)},
          {"run_id", plan.run_id},    {"run_dir", plan.run_dir},
          {"domain", plan.domain_id}, {"launcher_pid", launcher_pid}};
}

std::string make_summary(const LaunchPlan& plan, const RunOutcome& outcome) {
  std::ostringstream text;
  text << "run " << plan.run_id << " in " << plan.run_dir << "\n";
  for (const auto& [key, value] : plan.variables) {
    text << "  {" << key << "} = " << (value.empty() ? "\"\"" : value) << "\n";
  }
  for (const auto& process : outcome.processes) {
    text << "  " << process.name << " (" << process.dds << "): ";
    if (!process.pid) {
      text << "not started\n";
      continue;
    }
    text << "pid " << *process.pid << ", exit code "
         << (process.exit_code ? std::to_string(*process.exit_code) : "?");
    if (!process.stopped_by.empty()) text << ", stopped with " << process.stopped_by;
    if (process.cpu_s) text << ", " << *process.cpu_s << " s of CPU";
    if (process.respawns > 0) {
      text << ", respawned " << process.respawns << (process.respawns == 1 ? " time" : " times");
    }
    text << "\n";
  }
  text << outcome.reason << " -> exit code " << outcome.exit_code << "\n";
  return text.str();
}

}  // namespace cover::launch
