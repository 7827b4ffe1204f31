#pragma once

#include <cstdint>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/vocabulary/fleet_size.hpp"

namespace cover::foxglove {

// cover-foxglove-bridge's settings (config/foxglove_bridge.yaml, section `foxglove`; every
// key optional). Its command-line flags, where given, override them.
struct LiveViewParams {
  std::string address = "0.0.0.0";
  int port = 8765;  // 0: any free port (logged)
  int uavs = fleet::kDefaultUavs;
  int ugvs = fleet::kDefaultUgvs;
  // Bytes waiting for one client before its new messages are dropped, KiB (the others are
  // unaffected), and how long a full queue (a client that does not read) is borne.
  int client_queue_kib = 4096;
  double slow_client_timeout_s = 5.0;
  int max_clients = 16;
  double scene_rate_hz = 20.0;
  double deck_size_m = 1.0;
  double stale_after_s = 0.5;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("address", self.address, Field("", "address to listen on (0.0.0.0: every interface)"));
    visit("port", self.port,
          Field("", "TCP port of ws://HOST:PORT; 0: any free port, logged")
              .at_least(0.0)
              .at_most(65535.0));
    visit("uavs", self.uavs,
          Field("", "UAV ids 0..N-1 whose topics are served").at_least(1.0).at_most(64.0));
    visit("ugvs", self.ugvs,
          Field("", "UGV ids 0..N-1 whose topics are served").at_least(1.0).at_most(64.0));
    visit("client_queue_kib", self.client_queue_kib,
          Field("KiB", "bytes waiting for one client before its new messages are dropped")
              .at_least(64.0)
              .at_most(65536.0));
    visit("slow_client_timeout_s", self.slow_client_timeout_s,
          Field("s", "a client whose queue stays full this long (not reading) is disconnected")
              .at_least(0.1)
              .at_most(3600.0));
    visit("max_clients", self.max_clients,
          Field("", "connections served at once").at_least(1.0).at_most(256.0));
    visit("scene_rate_hz", self.scene_rate_hz,
          Field("Hz", "rate of cover/foxglove/tf and cover/foxglove/scene while subscribed")
              .at_least(0.1)
              .at_most(100.0));
    visit("deck_size_m", self.deck_size_m,
          Field("m", "side of the deck drawn at each UGV frame's origin")
              .at_least(0.1)
              .at_most(20.0));
    visit("stale_after_s", self.stale_after_s,
          Field("s", "a relative state older than this (by receive time) no longer places a frame")
              .above(0.0)
              .at_most(60.0));
  }

  static LiveViewParams load_file(const std::string& path);
  static LiveViewParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::foxglove
