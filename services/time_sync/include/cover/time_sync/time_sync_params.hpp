#pragma once

#include <string>

#include "cover/config/param_fields.hpp"

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

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list. peer_timeout_s > request_period_s is in validate().
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("max_offset_ms", self.max_offset_ms,
          Field("ms", "a UAV agent holds a task while |offset| to a peer exceeds this")
              .above(0.0)
              .at_most(10000.0));
    visit("request_period_s", self.request_period_s,
          Field("s", "one clock request per period once the filter is full")
              .above(0.0)
              .at_most(60.0));
    visit("burst_count", self.burst_count,
          Field("", "requests sent burst_period_s apart at start and when a peer appears")
              .at_least(0.0)
              .at_most(64.0));
    visit("burst_period_s", self.burst_period_s,
          Field("s", "the burst's spacing").above(0.0).at_most(10.0));
    visit("window_samples", self.window_samples,
          Field("", "the clock filter keeps the least-delay sample of the last N")
              .at_least(1.0)
              .at_most(64.0));
    visit("peer_timeout_s", self.peer_timeout_s,
          Field("s", "a peer that has not answered this long is forgotten; > request_period_s")
              .above(0.0)
              .at_most(3600.0));
  }

  static TimeSyncParams load_file(const std::string& path);
  // time_sync.yaml in the folder of `other_config` (a process's own --config file); the
  // defaults when there is none.
  static TimeSyncParams load_beside(const std::string& other_config);
  static TimeSyncParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::time_sync
