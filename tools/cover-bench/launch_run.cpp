#include "launch_run.hpp"

#include <unistd.h>

#include <fstream>
#include <iostream>

#include "cover/config/yaml_reader.hpp"
#include "cover/process/child_process.hpp"
#include "cover_binary.hpp"

namespace cover::bench {

namespace {}  // namespace

std::vector<std::string> launch_argv(const LaunchRequest& request) {
  std::vector<std::string> argv = {cover::bench::cover_binary("cover-launch"),
                                   request.launch_file,
                                   "--json",
                                   "--domain",
                                   std::to_string(request.domain),
                                   "--run-dir",
                                   request.run_dir.string()};
  argv.insert(argv.end(), request.flags.begin(), request.flags.end());
  return argv;
}

LaunchOutcome run_launcher(const LaunchRequest& request, const std::string& log_file,
                           std::chrono::milliseconds timeout) {
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = log_file;
  cover::process::ChildProcess child(launch_argv(request), options);
  LaunchOutcome outcome;
  while (const auto line = child.read_line(timeout)) outcome.stdout_text += *line + "\n";
  outcome.exit_code = child.wait(timeout).value_or(-1);
  outcome.result = nlohmann::json::parse(outcome.stdout_text, nullptr, false);
  return outcome;
}

std::optional<nlohmann::json> wait_for_run_identity(const std::filesystem::path& run_dir,
                                                    cover::process::ChildProcess& launch,
                                                    std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  const auto read = [file = run_dir / "run.json"]() -> std::optional<nlohmann::json> {
    std::ifstream in(file);  // written whole and renamed into place: never half of it
    if (!in) return std::nullopt;
    auto identity = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (!identity.is_object() || !identity["run_id"].is_string() ||
        !identity["domain"].is_number_integer()) {
      return std::nullopt;
    }
    return identity;
  };
  for (;;) {
    if (auto identity = read()) return identity;
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    // Polled while the launch lives (it writes the file before its first process starts);
    // once it has ended, the file is there or never will be.
    if (launch.wait(std::chrono::milliseconds(5))) return read();
  }
}

std::string launch_file_path(const std::string& launch_name) {
  return cover::config::default_config_dir() + "/launch/" + launch_name + ".yaml";
}

nlohmann::json run_launch(const std::string& launch_name, const std::vector<std::string>& flags,
                          int domain, const std::string& who, std::chrono::minutes timeout) {
  LaunchRequest request;
  request.launch_file = launch_file_path(launch_name);
  request.domain = domain;
  request.run_dir =
      std::filesystem::temp_directory_path() /
      ("cover_bench_" + who + "_" + std::to_string(getpid()) + "_" + std::to_string(domain));
  request.flags = flags;
  std::filesystem::remove_all(request.run_dir);
  // The launcher's own log lines would bury the benchmark's output: keep them in a file.
  const std::string log_file = request.run_dir.string() + ".log";
  const nlohmann::json result = run_launcher(request, log_file, timeout).result;
  if (result.is_object() && result.value("success", false)) {
    std::filesystem::remove_all(request.run_dir);
    std::filesystem::remove(log_file);
  } else {
    std::cerr << "cover-bench " << who << ": " << launch_name << " on domain " << domain
              << (result.is_object() ? " did not succeed" : " gave no result") << "; logs in "
              << request.run_dir.string() << " and " << log_file << "\n";
  }
  return result.is_object() ? result : nlohmann::json::object();
}

}  // namespace cover::bench
