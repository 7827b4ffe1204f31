#include "launch_run.hpp"

#include <unistd.h>

#include <filesystem>
#include <iostream>

#include "cover/config/yaml_reader.hpp"
#include "cover/process/child_process.hpp"

namespace cover::bench {

namespace {

#ifdef COVER_LAUNCH
constexpr const char* kLaunch = COVER_LAUNCH;
#else
constexpr const char* kLaunch = "cover-launch";
#endif

}  // namespace

nlohmann::json run_launch(const std::string& launch_name, const std::vector<std::string>& flags,
                          int domain, const std::string& who, std::chrono::minutes timeout) {
  const std::filesystem::path run_dir =
      std::filesystem::temp_directory_path() /
      ("cover_bench_" + who + "_" + std::to_string(getpid()) + "_" + std::to_string(domain));
  std::filesystem::remove_all(run_dir);
  std::vector<std::string> argv = {
      kLaunch,
      cover::config::default_config_dir() + "/launch/" + launch_name + ".yaml",
      "--json",
      "--domain",
      std::to_string(domain),
      "--run-dir",
      run_dir.string()};
  argv.insert(argv.end(), flags.begin(), flags.end());
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  // The launcher's own log lines would bury the benchmark's output: keep them in a file.
  options.log_file = run_dir.string() + ".log";
  cover::process::ChildProcess child(argv, options);
  std::string out;
  while (const auto line = child.read_line(timeout)) out += *line + "\n";
  child.wait(std::chrono::minutes(1));
  const nlohmann::json result = nlohmann::json::parse(out, nullptr, false);
  if (result.is_object() && result.value("success", false)) {
    std::filesystem::remove_all(run_dir);
    std::filesystem::remove(options.log_file);
  } else {
    std::cerr << "cover-bench " << who << ": " << launch_name << " on domain " << domain
              << (result.is_object() ? " did not succeed" : " gave no result") << "; logs in "
              << run_dir.string() << " and " << options.log_file << "\n";
  }
  return result.is_object() ? result : nlohmann::json::object();
}

}  // namespace cover::bench
