#include "cover/mocap/relay_params.hpp"

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>

#include "cover/vrpn/tracker_client.hpp"

namespace cover::mocap {
namespace {

std::vector<BodyBinding> read_bodies(config::YamlReader& reader) {
  std::vector<BodyBinding> bodies;
  config::YamlReader map = reader.child("bodies");
  if (!map.node().IsDefined() || map.node().IsNull()) return bodies;
  config::check(map.node().IsMap(), reader.context() + ".bodies",
                "must map uav<u> / ugv<k> to the server's body names");
  static const std::regex key_pattern("(uav|ugv)([0-9]{1,3})");
  for (const auto& entry : map.node()) {
    const std::string key = entry.first.as<std::string>();
    std::smatch m;
    config::check(std::regex_match(key, m, key_pattern), reader.context() + ".bodies." + key,
                  "keys are uav<u> or ugv<k> (uav0, ugv1)");
    BodyBinding b;
    b.vehicle = m[1] == "uav" ? BodyBinding::Vehicle::Uav : BodyBinding::Vehicle::Ugv;
    b.id = std::stoi(m[2]);
    map.optional(key, b.name);
    bodies.push_back(b);
  }
  return bodies;
}

}  // namespace

RelayParams RelayParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

RelayParams RelayParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "mocap", true);
  RelayParams p;
  reader.require("server", p.server);
  reader.optional("up_axis", p.up_axis);
  reader.optional("units", p.units);
  p.bodies = read_bodies(reader);
  reader.optional("jump_gate_m", p.jump_gate_m);
  reader.optional("jump_reset_s", p.jump_reset_s);
  reader.optional("lost_after_s", p.lost_after_s);
  reader.optional("warmup_updates", p.warmup_updates);
  reader.optional("frame_timeout_s", p.frame_timeout_s);
  reader.optional("time_source", p.time_source);
  reader.optional("offset_window_s", p.offset_window_s);
  reader.optional("connect_timeout_s", p.connect_timeout_s);
  reader.optional("backoff_min_s", p.backoff_min_s);
  reader.optional("backoff_max_s", p.backoff_max_s);
  reader.optional("silence_timeout_s", p.silence_timeout_s);
  config::YamlReader filter = reader.child("filter");
  filter.optional("accel_noise_m_s2", p.filter.accel_noise_m_s2);
  filter.optional("position_noise_m", p.filter.position_noise_m);
  filter.optional("yaw_jerk_noise_rad_s3", p.filter.yaw_jerk_noise_rad_s3);
  filter.optional("yaw_noise_rad", p.filter.yaw_noise_rad);
  filter.reject_unknown_keys();
  reader.reject_unknown_keys();
  p.validate();
  return p;
}

void RelayParams::validate() const {
  auto in = [](double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  try {
    std::string host;
    std::uint16_t port = 0;
    vrpn::parse_server(server, host, port);
  } catch (const std::invalid_argument& e) {
    config::check(false, "mocap.server", e.what());
  }
  config::check(up_axis == "z" || up_axis == "y", "mocap.up_axis", "must be z or y");
  config::check(units == "m" || units == "mm", "mocap.units", "must be m or mm");
  config::check(!uav_ids().empty() && !ugv_ids().empty(), "mocap.bodies",
                "needs at least one uav<u> and one ugv<k>");
  std::set<std::string> names;
  for (const auto& b : bodies) {
    config::check(!b.name.empty(), "mocap.bodies." + b.key(), "needs the server's body name");
    config::check(names.insert(b.name).second, "mocap.bodies." + b.key(),
                  "'" + b.name + "' is named twice");
    config::check(b.id < 256, "mocap.bodies." + b.key(), "ids go up to 255");
  }
  config::check(in(filter.accel_noise_m_s2, 1e-3, 1e3), "mocap.filter.accel_noise_m_s2",
                "must be in [0.001, 1000]");
  config::check(in(filter.position_noise_m, 1e-6, 1.0), "mocap.filter.position_noise_m",
                "must be in [1e-6, 1] m");
  config::check(in(filter.yaw_jerk_noise_rad_s3, 1e-3, 1e4), "mocap.filter.yaw_jerk_noise_rad_s3",
                "must be in [0.001, 10000]");
  config::check(in(filter.yaw_noise_rad, 1e-6, 1.0), "mocap.filter.yaw_noise_rad",
                "must be in [1e-6, 1] rad");
  config::check(in(jump_gate_m, 0.001, 100.0), "mocap.jump_gate_m", "must be in [0.001, 100] m");
  config::check(in(jump_reset_s, 0.0, 10.0), "mocap.jump_reset_s", "must be in [0, 10] s");
  config::check(in(lost_after_s, 0.001, 5.0), "mocap.lost_after_s", "must be in [0.001, 5] s");
  config::check(warmup_updates >= 2 && warmup_updates <= 100, "mocap.warmup_updates",
                "must be in [2, 100]");
  config::check(in(frame_timeout_s, 0.0, 0.1), "mocap.frame_timeout_s", "must be in [0, 0.1] s");
  config::check(time_source == "server" || time_source == "offset", "mocap.time_source",
                "must be server or offset");
  config::check(in(offset_window_s, 0.1, 3600.0), "mocap.offset_window_s",
                "must be in [0.1, 3600] s");
  config::check(in(connect_timeout_s, 0.01, 60.0), "mocap.connect_timeout_s",
                "must be in [0.01, 60] s");
  config::check(in(backoff_min_s, 0.01, 60.0) && in(backoff_max_s, backoff_min_s, 600.0),
                "mocap.backoff_min_s", "must satisfy 0.01 <= backoff_min_s <= backoff_max_s");
  config::check(in(silence_timeout_s, 0.05, 60.0), "mocap.silence_timeout_s",
                "must be in [0.05, 60] s");
}

std::vector<int> RelayParams::uav_ids() const {
  std::vector<int> ids;
  for (const auto& b : bodies) {
    if (b.vehicle == BodyBinding::Vehicle::Uav) ids.push_back(b.id);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<int> RelayParams::ugv_ids() const {
  std::vector<int> ids;
  for (const auto& b : bodies) {
    if (b.vehicle == BodyBinding::Vehicle::Ugv) ids.push_back(b.id);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace cover::mocap
