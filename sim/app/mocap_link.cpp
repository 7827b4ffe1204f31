#include "mocap_link.hpp"

#include <spdlog/spdlog.h>

#include "cover/config/config_error.hpp"
#include "cover/wire/eigen.hpp"
#include "fleet.hpp"

namespace cover::sim {
namespace {

mocap::ServerOptions server_options(const Fleet& fleet, const MocapRunOptions& options) {
  mocap::ServerOptions s;
  s.bind_address = options.bind_address;
  s.port = options.port;
  s.bodies = mocap::body_names(options.params, fleet.world(0).ugv_count(), fleet.uav_count());
  return s;
}

}  // namespace

MocapRunOptions parse_mocap_option(const std::string& value, const std::string& config_file) {
  MocapRunOptions o;
  if (value.empty()) return o;
  const std::string prefix = "vrpn";
  if (value.compare(0, prefix.size(), prefix) != 0 ||
      (value.size() > prefix.size() && value[prefix.size()] != ':')) {
    throw config::ConfigError("--mocap: expected vrpn or vrpn:PORT (got '" + value + "')");
  }
  if (value.size() > prefix.size()) {
    const std::string digits = value.substr(prefix.size() + 1);
    int port = -1;
    try {
      std::size_t used = 0;
      port = std::stoi(digits, &used);
      if (used != digits.size()) port = -1;
    } catch (const std::exception&) {
      port = -1;
    }
    if (port < 1 || port > 65535) {
      throw config::ConfigError("--mocap: PORT must be in [1, 65535] (got '" + digits + "')");
    }
    o.port = static_cast<std::uint16_t>(port);
  }
  o.enabled = true;
  o.params = mocap::MocapServerParams::load_file(config_file);
  return o;
}

MocapLink::MocapLink(const Fleet& fleet, const MocapRunOptions& options)
    : options_(options),
      server_(server_options(fleet, options)),
      feed_(options.params, server_.bodies().size()),
      truth_(server_.bodies().size()) {
  const auto& p = options_.params;
  spdlog::info(
      "mocap: VRPN server on {} ({} bodies: {}..), {:.0f} Hz, latency {:.0f} ms, noise {:.1f} mm "
      "/ {:.1f} mrad, dropouts {:.1f} %, {} up, {}; relative states come from a "
      "cover-mocap-relay",
      describe(), server_.bodies().size(), server_.bodies().front(), p.rate_hz, p.latency_s * 1e3,
      p.position_noise_m * 1e3, p.attitude_noise_rad * 1e3, p.dropout_probability * 100.0,
      p.up_axis, p.units);
}

std::string MocapLink::describe() const {
  return options_.bind_address + ":" + std::to_string(server_.port());
}

bool MocapLink::wait_for_client(std::chrono::milliseconds timeout) const {
  return server_.wait_for_clients(1, timeout);
}

std::int64_t MocapLink::serve(const Fleet& fleet, bool withheld) {
  if (fleet.tick() == served_tick_) {
    // The tick published again (an agent has not answered): so is its newest frame, whose
    // relative states may have been lost on their way (the relay writes them again).
    if (withheld || !last_sent_) return -1;
    server_.send_frame(last_sent_->capture_ns, last_sent_->poses);
    return newest_sent_ns_;
  }
  served_tick_ = fleet.tick();
  const WorldState& world = fleet.world(0).state();
  const int ugvs = fleet.world(0).ugv_count();
  for (int k = 0; k < ugvs; ++k) {
    truth_[k].position_m = world.ugvs[k].position_m.eigen();
    truth_[k].attitude = world.ugvs[k].attitude();
  }
  for (int u = 0; u < fleet.uav_count(); ++u) {
    const QuadrotorState& uav = fleet.world(u).state().uav;
    truth_[ugvs + u].position_m = uav.position_m.eigen();
    truth_[ugvs + u].attitude = uav.attitude.eigen();
  }
  released_.clear();
  feed_.step(wire::to_stamp_ns(fleet.time_s()), truth_, released_);
  if (withheld) return -1;
  for (const auto& frame : released_) {
    server_.send_frame(frame.capture_ns, frame.poses);
    newest_sent_ns_ = frame.capture_ns;
    last_sent_ = frame;
  }
  return newest_sent_ns_;
}

}  // namespace cover::sim
