#include "cover/time_sync/time_sync_params.hpp"

#include <cmath>
#include <filesystem>

namespace cover::time_sync {

TimeSyncParams TimeSyncParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

TimeSyncParams TimeSyncParams::load_beside(const std::string& other_config) {
  const std::filesystem::path path =
      std::filesystem::path(other_config).parent_path() / "time_sync.yaml";
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return TimeSyncParams{};
  return load_file(path.string());
}

TimeSyncParams TimeSyncParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "time_sync", false);
  TimeSyncParams p;
  reader.optional("max_offset_ms", p.max_offset_ms);
  reader.optional("request_period_s", p.request_period_s);
  reader.optional("burst_count", p.burst_count);
  reader.optional("burst_period_s", p.burst_period_s);
  reader.optional("window_samples", p.window_samples);
  reader.optional("peer_timeout_s", p.peer_timeout_s);
  reader.reject_unknown_keys();
  p.validate();
  return p;
}

void TimeSyncParams::validate() const {
  auto in = [](double v, double lo, double hi) { return std::isfinite(v) && v > lo && v <= hi; };
  config::check(in(max_offset_ms, 0.0, 10000.0), "time_sync.max_offset_ms",
                "must be in (0, 10000]");
  config::check(in(request_period_s, 0.0, 60.0), "time_sync.request_period_s",
                "must be in (0, 60]");
  config::check(burst_count >= 0 && burst_count <= 64, "time_sync.burst_count",
                "must be in [0, 64]");
  config::check(in(burst_period_s, 0.0, 10.0), "time_sync.burst_period_s", "must be in (0, 10]");
  config::check(window_samples >= 1 && window_samples <= 64, "time_sync.window_samples",
                "must be in [1, 64]");
  config::check(in(peer_timeout_s, request_period_s, 3600.0), "time_sync.peer_timeout_s",
                "must be > request_period_s and <= 3600");
}

}  // namespace cover::time_sync
