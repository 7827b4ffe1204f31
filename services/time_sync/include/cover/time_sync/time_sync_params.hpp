#pragma once

#include <string>

#include "cover/config/yaml_reader.hpp"

namespace cover::time_sync {

// The clock exchange's settings (config/time_sync.yaml, section `time_sync`).
struct TimeSyncParams {
  // A UAV agent does not start a task while its clock is further than this from a peer
  // whose samples it takes (the ladder calls an input stale after 100 ms), ms.
  double max_offset_ms = 20.0;
  double request_period_s = 1.0;  // one request a second once the filter is full
  // At start and when a peer (re)appears: this many requests, this far apart, so that an
  // estimate exists within a fraction of a second (NTP's iburst).
  int burst_count = 8;
  double burst_period_s = 0.1;
  int window_samples = 8;       // the clock filter keeps the least-delay of the last N
  double peer_timeout_s = 5.0;  // a peer that has not answered this long is forgotten

  static TimeSyncParams load_file(const std::string& path);
  // time_sync.yaml in the folder of `other_config` (a process's own --config file); the
  // defaults when there is none.
  static TimeSyncParams load_beside(const std::string& other_config);
  static TimeSyncParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::time_sync
