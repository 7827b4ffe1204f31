#include "cover/time_sync/time_sync_params.hpp"

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
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void TimeSyncParams::validate() const {
  config::check_fields(*this, "time_sync");
  config::check(peer_timeout_s > request_period_s, "time_sync.peer_timeout_s",
                "must be > request_period_s");
}

}  // namespace cover::time_sync
