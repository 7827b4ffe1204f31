#include "cover/launch/run_naming.hpp"

#include <cctype>
#include <ctime>
#include <filesystem>

namespace cover::launch {

std::string sanitize_run_id(const std::string& text) {
  std::string id = text;
  for (char& c : id) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  }
  return id;
}

std::string make_run_id(const std::string& launch_name, pid_t launcher_pid) {
  return sanitize_run_id(launch_name + "_" + std::to_string(launcher_pid));
}

std::string default_run_dir(const std::string& base_dir, const std::string& launch_name,
                            std::chrono::system_clock::time_point now) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  std::tm local{};
  localtime_r(&seconds, &local);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &local);
  const auto base = std::filesystem::path(base_dir) / "runs" / (launch_name + "_" + stamp);
  auto candidate = base;
  for (int suffix = 2; std::filesystem::exists(candidate); ++suffix) {
    candidate = base.string() + "_" + std::to_string(suffix);
  }
  return candidate.string();
}

}  // namespace cover::launch
