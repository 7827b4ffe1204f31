#include "cover/mocap/relative_estimator.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

namespace cover::mocap {

RelativeEstimator::RelativeEstimator(const RelayParams& params) : params_(params) {
  filters_.reserve(params_.bodies.size());
  for (std::size_t i = 0; i < params_.bodies.size(); ++i) filters_.emplace_back(params_);
  lost_logged_.assign(params_.bodies.size(), false);
  for (std::size_t a = 0; a < params_.bodies.size(); ++a) {
    if (params_.bodies[a].vehicle != BodyBinding::Vehicle::Uav) continue;
    for (std::size_t g = 0; g < params_.bodies.size(); ++g) {
      if (params_.bodies[g].vehicle != BodyBinding::Vehicle::Ugv) continue;
      pairs_.push_back(
          {static_cast<int>(a), static_cast<int>(g), params_.bodies[a].id, params_.bodies[g].id});
    }
  }
}

std::vector<std::pair<int, int>> RelativeEstimator::pair_ids() const {
  std::vector<std::pair<int, int>> ids;
  for (const Pair& p : pairs_) ids.emplace_back(p.uav, p.ugv);
  return ids;
}

void RelativeEstimator::note_body(std::size_t body, BodyFilter::Update update,
                                  const BodySample& sample, std::int64_t server_ns) {
  const BodyBinding& b = params_.bodies[body];
  const double t_s = static_cast<double>(server_ns) * 1e-9;
  switch (update) {
    case BodyFilter::Update::Started:
      spdlog::info("body {} ('{}') seen at t = {:.3f} s", b.key(), b.name, t_s);
      break;
    case BodyFilter::Update::Restarted:
      ++stats_.restarts;
      spdlog::info("body {} ('{}') tracked again at t = {:.3f} s (filter restarted)", b.key(),
                   b.name, t_s);
      break;
    case BodyFilter::Update::Jump:
      ++stats_.jumps;
      if (!filters_[body].jumping() || stats_.jumps % 100 == 1) {
        spdlog::warn("body {} ('{}') jumped {:.3f} m at t = {:.3f} s (gate {:.3f} m): rejected",
                     b.key(), b.name,
                     (sample.pose.position_m - filters_[body].position_at(server_ns)).norm(), t_s,
                     params_.jump_gate_m);
      }
      break;
    case BodyFilter::Update::Accepted:
      break;
  }
  lost_logged_[body] = false;
}

void RelativeEstimator::on_frame(const Frame& frame, std::int64_t stamp_ns,
                                 std::vector<RelativeOutput>& out) {
  ++stats_.frames;
  for (std::size_t i = 0; i < filters_.size() && i < frame.bodies.size(); ++i) {
    const BodySample& sample = frame.bodies[i];
    if (!sample.reported || !sample.valid) continue;
    note_body(i, filters_[i].measure(frame.server_ns, sample.pose), sample, frame.server_ns);
  }
  out.resize(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    Pair& pair = pairs_[p];
    out[p] = relative(pair, frame.server_ns, stamp_ns);
    if (!out[p].valid) ++stats_.invalid_outputs;
    if (out[p].valid != pair.was_valid || !pair.ever) {
      const double t_s = static_cast<double>(frame.server_ns) * 1e-9;
      if (out[p].valid) {
        spdlog::info("uav{} in ugv{}: valid at t = {:.3f} s", pair.uav, pair.ugv, t_s);
      } else {
        spdlog::warn("uav{} in ugv{}: invalid at t = {:.3f} s ({})", pair.uav, pair.ugv, t_s,
                     why_invalid(pair, frame.server_ns));
      }
    }
    pair.was_valid = out[p].valid;
    pair.ever = true;
  }
}

std::string RelativeEstimator::why_invalid(const Pair& pair, std::int64_t server_ns) const {
  std::string why;
  for (const int body : {pair.uav_body, pair.ugv_body}) {
    const BodyFilter& f = filters_[static_cast<std::size_t>(body)];
    const BodyBinding& b = params_.bodies[static_cast<std::size_t>(body)];
    if (f.tracked_at(server_ns)) continue;
    if (!why.empty()) why += "; ";
    if (!f.started()) {
      why += b.key() + " ('" + b.name + "') never seen";
    } else if (f.jumping()) {
      why += b.key() + " ('" + b.name + "') jumping";
    } else if (static_cast<double>(server_ns - f.last_measured_ns()) > params_.lost_after_s * 1e9) {
      why += b.key() + " ('" + b.name + "') not seen for " +
             std::to_string(static_cast<int>((server_ns - f.last_measured_ns()) / 1'000'000)) +
             " ms";
    } else {
      why += b.key() + " ('" + b.name + "') warming up";
    }
  }
  return why;
}

RelativeOutput RelativeEstimator::relative(const Pair& pair, std::int64_t server_ns,
                                           std::int64_t stamp_ns) const {
  const BodyFilter& uav = filters_[static_cast<std::size_t>(pair.uav_body)];
  const BodyFilter& ugv = filters_[static_cast<std::size_t>(pair.ugv_body)];
  RelativeOutput o;
  o.uav = pair.uav;
  o.ugv = pair.ugv;
  o.stamp_ns = stamp_ns;
  o.state.stamp_s = static_cast<double>(stamp_ns) * 1e-9;
  o.valid = uav.tracked_at(server_ns) && ugv.tracked_at(server_ns);
  if (!uav.started() || !ugv.started()) return o;  // zeros, identity: nothing known
  const Eigen::Quaterniond ugv_attitude = ugv.attitude_at(server_ns);
  const Eigen::Quaterniond world_to_ugv = ugv_attitude.inverse();
  const Eigen::Vector3d p =
      world_to_ugv * (uav.position_at(server_ns) - ugv.position_at(server_ns));
  const Eigen::Vector3d omega_in_ugv =
      world_to_ugv * Eigen::Vector3d(0.0, 0.0, ugv.yaw_rate_rad_s());
  o.state.position_m = p;
  o.state.velocity_m_s = world_to_ugv * (uav.velocity() - ugv.velocity()) - omega_in_ugv.cross(p);
  o.state.attitude = (world_to_ugv * uav.measured_attitude()).normalized();
  o.position_std_m = std::hypot(uav.position_std_m(), ugv.position_std_m());
  // Never a NaN on the wire, whatever came in.
  const bool finite = o.state.position_m.allFinite() && o.state.velocity_m_s.allFinite() &&
                      o.state.attitude.coeffs().allFinite() && std::isfinite(o.position_std_m);
  if (!finite) {
    o = RelativeOutput{pair.uav, pair.ugv, stamp_ns, {}, false, 0.0};
    o.state.stamp_s = static_cast<double>(stamp_ns) * 1e-9;
  }
  return o;
}

}  // namespace cover::mocap
