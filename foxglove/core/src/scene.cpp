#include "cover/foxglove/scene.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <deque>

namespace cover::foxglove {
namespace {

using nlohmann::json;

json stamp(std::int64_t ns) {
  const std::int64_t clamped = ns < 0 ? 0 : ns;
  return {{"sec", clamped / 1'000'000'000}, {"nsec", clamped % 1'000'000'000}};
}

json vec(const msg::Vector3& v) {
  return {{"x", v.x}, {"y", v.y}, {"z", v.z}};
}

json vec(double x, double y, double z) {
  return {{"x", x}, {"y", y}, {"z", z}};
}

json quat(const msg::Quaternion& q) {
  return {{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}};
}

json identity_pose() {
  return {{"position", vec(0, 0, 0)}, {"orientation", {{"x", 0}, {"y", 0}, {"z", 0}, {"w", 1}}}};
}

json color(double r, double g, double b, double a) {
  return {{"r", r}, {"g", g}, {"b", b}, {"a", a}};
}

json entity(const std::string& id, const std::string& frame, std::int64_t now_ns) {
  return {
      {"timestamp", stamp(now_ns)},       {"frame_id", frame},      {"id", id},
      {"lifetime", stamp(1'000'000'000)}, {"frame_locked", true},   {"metadata", json::array()},
      {"arrows", json::array()},          {"cubes", json::array()}, {"spheres", json::array()},
      {"cylinders", json::array()},       {"lines", json::array()}, {"triangles", json::array()},
      {"texts", json::array()},           {"models", json::array()}};
}

json label(const std::string& text, double z) {
  return {{"pose", {{"position", vec(0, 0, z)}, {"orientation", quat({1, 0, 0, 0})}}},
          {"billboard", true},
          {"font_size", 14.0},
          {"scale_invariant", true},
          {"color", color(1, 1, 1, 1)},
          {"text", text}};
}

// The state's attitude rotates UAV body vectors into G_k: the transform of child uav_<u>
// in parent ugv_<k>. Its inverse places G_k in the UAV's frame.
void invert(const msg::Vector3& t, const msg::Quaternion& q, msg::Vector3& t_inv,
            msg::Quaternion& q_inv) {
  const Eigen::Quaterniond rotation = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized();
  const Eigen::Quaterniond inverse = rotation.conjugate();
  const Eigen::Vector3d translation = -(inverse * Eigen::Vector3d(t.x, t.y, t.z));
  t_inv = {translation.x(), translation.y(), translation.z()};
  q_inv = {inverse.w(), inverse.x(), inverse.y(), inverse.z()};
}

}  // namespace

Scene::Scene(SceneOptions options)
    : options_(options),
      states_(static_cast<std::size_t>(options.uavs) * options.ugvs),
      received_ns_(states_.size(), 0),
      references_(options.uavs) {}

void Scene::on_relative_state(const msg::RelativeState& state, std::int64_t received_ns) {
  if (state.uav_id >= options_.uavs || state.ugv_id >= options_.ugvs) return;
  const std::size_t i = static_cast<std::size_t>(state.uav_id) * options_.ugvs + state.ugv_id;
  std::lock_guard<std::mutex> lock(mutex_);
  states_[i] = state;
  received_ns_[i] = received_ns;
}

void Scene::on_reference(const msg::ReferenceTrajectory& reference) {
  if (reference.uav_id >= options_.uavs) return;
  std::lock_guard<std::mutex> lock(mutex_);
  references_[reference.uav_id] = reference;
}

std::vector<Scene::Transform> Scene::spanning_forest(std::int64_t now_ns) const {
  const auto stale_ns = static_cast<std::int64_t>(options_.stale_after_s * 1e9);
  auto fresh = [&](std::uint32_t u, std::uint32_t k) -> const msg::RelativeState* {
    const std::size_t i = static_cast<std::size_t>(u) * options_.ugvs + k;
    const auto& s = states_[i];
    if (!s || !s->valid || now_ns - received_ns_[i] > stale_ns) return nullptr;
    return &*s;
  };
  std::vector<bool> ugv_seen(options_.ugvs, false);
  std::vector<bool> uav_seen(options_.uavs, false);
  std::vector<Transform> out;
  for (std::uint32_t root = 0; root < options_.ugvs; ++root) {
    if (ugv_seen[root]) continue;
    ugv_seen[root] = true;
    // Breadth first over (is_ugv, id): a UGV reaches the UAVs it has states of, a UAV the
    // UGVs it has states in.
    std::deque<std::pair<bool, std::uint32_t>> open{{true, root}};
    while (!open.empty()) {
      const auto [is_ugv, id] = open.front();
      open.pop_front();
      if (is_ugv) {
        for (std::uint32_t u = 0; u < options_.uavs; ++u) {
          const auto* s = fresh(u, id);
          if (uav_seen[u] || s == nullptr) continue;
          uav_seen[u] = true;
          out.push_back({ugv_frame(id), uav_frame(u), s->position_m, s->attitude});
          open.emplace_back(false, u);
        }
      } else {
        for (std::uint32_t k = 0; k < options_.ugvs; ++k) {
          const auto* s = fresh(id, k);
          if (ugv_seen[k] || s == nullptr) continue;
          ugv_seen[k] = true;
          Transform t{uav_frame(id), ugv_frame(k), {}, {}};
          invert(s->position_m, s->attitude, t.translation, t.rotation);
          out.push_back(t);
          open.emplace_back(true, k);
        }
      }
    }
  }
  return out;
}

std::vector<std::string> Scene::frame_transforms(std::int64_t now_ns) const {
  std::vector<Transform> forest;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    forest = spanning_forest(now_ns);
  }
  std::vector<std::string> out;
  for (const auto& t : forest) {
    out.push_back(json{{"timestamp", stamp(now_ns)},
                       {"parent_frame_id", t.parent},
                       {"child_frame_id", t.child},
                       {"translation", vec(t.translation)},
                       {"rotation", quat(t.rotation)}}
                      .dump());
  }
  return out;
}

std::string Scene::scene_update(std::int64_t now_ns) const {
  std::vector<Transform> forest;
  std::vector<msg::ReferenceTrajectory> references;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    forest = spanning_forest(now_ns);
    for (const auto& r : references_) {
      if (r) references.push_back(*r);
    }
  }
  std::vector<std::string> frames;  // every frame of the forest, once
  for (const auto& t : forest) {
    for (const auto* frame : {&t.parent, &t.child}) {
      if (std::find(frames.begin(), frames.end(), *frame) == frames.end()) frames.push_back(*frame);
    }
  }
  json entities = json::array();
  const double deck = options_.deck_size_m;
  for (const auto& frame : frames) {
    json e = entity(frame, frame, now_ns);
    if (frame.rfind("ugv_", 0) == 0) {
      e["cubes"].push_back({{"pose", identity_pose()},
                            {"size", vec(deck, deck, 0.02)},
                            {"color", color(0.2, 0.5, 0.9, 0.6)}});
      e["texts"].push_back(label(frame, 0.3));
    } else {
      e["cubes"].push_back({{"pose", identity_pose()},
                            {"size", vec(0.35, 0.35, 0.08)},
                            {"color", color(0.95, 0.55, 0.1, 0.9)}});
      e["arrows"].push_back({{"pose", identity_pose()},
                             {"shaft_length", 0.4},
                             {"shaft_diameter", 0.03},
                             {"head_length", 0.1},
                             {"head_diameter", 0.08},
                             {"color", color(0.95, 0.2, 0.1, 1.0)}});
      e["texts"].push_back(label(frame, 0.3));
    }
    entities.push_back(std::move(e));
  }
  for (const auto& r : references) {
    json e = entity("reference_" + std::to_string(r.uav_id), ugv_frame(r.reference_ugv), now_ns);
    json points = json::array();
    for (const auto& p : r.positions_m) points.push_back(vec(p));
    e["lines"].push_back({{"type", 0},
                          {"pose", identity_pose()},
                          {"thickness", 0.03},
                          {"scale_invariant", false},
                          {"points", std::move(points)},
                          {"color", color(0.1, 0.9, 0.3, 1.0)},
                          {"colors", json::array()},
                          {"indices", json::array()}});
    e["lifetime"] = stamp(0);  // until the next reference replaces it
    entities.push_back(std::move(e));
  }
  return json{{"deletions", json::array()}, {"entities", std::move(entities)}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

}  // namespace cover::foxglove
