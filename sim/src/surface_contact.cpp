#include "cover/sim/surface_contact.hpp"

#include <algorithm>
#include <cmath>

namespace cover::sim {

namespace {

double yaw_of(const Eigen::Quaterniond& attitude) {
  const Eigen::Matrix3d r = attitude.toRotationMatrix();
  return std::atan2(r(1, 0), r(0, 0));
}

}  // namespace

SurfaceContact::SurfaceContact(const std::array<UgvState, kMaxUgvs>& ugv_states, int ugv_count,
                               const std::vector<UgvParams>& ugv_params)
    : ugv_states_(ugv_states), ugv_count_(ugv_count), ugv_params_(ugv_params) {}

SurfaceContact::Hit SurfaceContact::penetrated(const Eigen::Vector3d& point_m) const {
  for (int k = 0; k < ugv_count_; ++k) {
    const Eigen::Vector3d local = ugv_states_[k].to_body(point_m);
    const UgvParams& ugv = ugv_params_[k];
    if (local.z() < 0.0 && std::abs(local.x()) <= ugv.deck_half_length_m &&
        std::abs(local.y()) <= ugv.deck_half_width_m) {
      return {true, k};
    }
  }
  if (point_m.z() < 0.0) return {true, -1};
  return {};
}

double SurfaceContact::height_m(std::int32_t surface) const {
  return surface < 0 ? 0.0 : ugv_states_[surface].position_m.z;
}

double SurfaceContact::yaw_rad(std::int32_t surface) const {
  return surface < 0 ? 0.0 : ugv_states_[surface].yaw_rad;
}

double SurfaceContact::yaw_rate_rad_s(std::int32_t surface) const {
  return surface < 0 ? 0.0 : ugv_states_[surface].yaw_rate_rad_s;
}

Eigen::Vector3d SurfaceContact::point_velocity_m_s(std::int32_t surface,
                                                   const Eigen::Vector3d& point_m) const {
  return surface < 0 ? Eigen::Vector3d::Zero() : ugv_states_[surface].point_velocity_m_s(point_m);
}

Eigen::Vector3d SurfaceContact::to_world(std::int32_t surface,
                                         const Eigen::Vector3d& offset_m) const {
  return surface < 0 ? offset_m : ugv_states_[surface].to_world(offset_m);
}

Eigen::Vector3d SurfaceContact::to_surface(std::int32_t surface,
                                           const Eigen::Vector3d& point_m) const {
  return surface < 0 ? point_m : ugv_states_[surface].to_body(point_m);
}

void SurfaceContact::start_resting(ContactState& contact, std::int32_t surface,
                                   const Eigen::Vector3d& point_m, double yaw_rad) const {
  Eigen::Vector3d on_top = point_m;
  on_top.z() = height_m(surface);
  contact.resting = true;
  contact.surface = surface;
  contact.offset_in_surface_m = Vec3(to_surface(surface, on_top));
  contact.yaw_offset_rad = yaw_rad - this->yaw_rad(surface);
}

void SurfaceContact::carry(const ContactState& contact, QuadrotorState& body) const {
  const Eigen::Vector3d position = to_world(contact.surface, contact.offset_in_surface_m.eigen());
  body.position_m = Vec3(position);
  body.velocity_m_s = Vec3(point_velocity_m_s(contact.surface, position));
  body.attitude = Quat(yaw_quaternion(yaw_rad(contact.surface) + contact.yaw_offset_rad));
  body.body_rate_rad_s = Vec3(0.0, 0.0, yaw_rate_rad_s(contact.surface));
}

void SurfaceContact::resolve(QuadrotorState& body, ContactState& contact, double mass_kg,
                             double gravity_m_s2) const {
  auto can_lift_off = [&] {
    const double vertical_thrust =
        body.attitude.eigen().toRotationMatrix()(2, 2) * body.thrust_n / mass_kg;
    return vertical_thrust > gravity_m_s2;
  };

  if (contact.resting) {
    if (!can_lift_off()) {
      carry(contact, body);
      return;
    }
    contact.resting = false;  // thrust exceeds weight: leave the surface
  }

  const Eigen::Vector3d position = body.position_m.eigen();
  const Hit hit = penetrated(position);
  if (!hit.hit) return;
  if (!can_lift_off()) {
    start_resting(contact, hit.surface, position, yaw_of(body.attitude.eigen()));
    carry(contact, body);
    return;
  }
  // Touching while thrusting upward (e.g. just after lift-off): stay on top, never sink.
  body.position_m.z = height_m(hit.surface);
  const double surface_vz = point_velocity_m_s(hit.surface, position).z();
  body.velocity_m_s.z = std::max(body.velocity_m_s.z, surface_vz);
}

}  // namespace cover::sim
