#include "cover/mocap/relay_params.hpp"

#include <algorithm>
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
  p.bodies = read_bodies(reader);
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void RelayParams::validate() const {
  config::check_fields(*this, "mocap");
  try {
    std::string host;
    std::uint16_t port = 0;
    vrpn::parse_server(server, host, port);
  } catch (const std::invalid_argument& e) {
    config::check(false, "mocap.server", e.what());
  }
  config::check(!uav_ids().empty() && !ugv_ids().empty(), "mocap.bodies",
                "needs at least one uav<u> and one ugv<k>");
  std::set<std::string> names;
  for (const auto& b : bodies) {
    config::check(!b.name.empty(), "mocap.bodies." + b.key(), "needs the server's body name");
    config::check(names.insert(b.name).second, "mocap.bodies." + b.key(),
                  "'" + b.name + "' is named twice");
    config::check(b.id < 256, "mocap.bodies." + b.key(), "ids go up to 255");
  }
  config::check(backoff_max_s >= backoff_min_s, "mocap.backoff_max_s", "must be >= backoff_min_s");
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
