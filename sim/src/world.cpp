#include "cover/sim/world.hpp"

#include "cover/clock/clock.hpp"

#include <cmath>

#include "cover/sim/seeding.hpp"

namespace cover::sim {

namespace {

// Seed streams of the world's random sources (IMU streams use 0..kMaxUgvs-1 internally).
constexpr std::uint64_t kRelativeSensorStream = 100;
constexpr std::uint64_t kImuStream = 200;
constexpr std::uint64_t kOdometryStream = 300;
constexpr std::uint64_t kMotorUavStream = 400;

const WorldParams& validated(const WorldParams& params) {
  params.validate();
  return params;
}

bool is_finite(const QuadrotorCommand& command) {
  return std::isfinite(command.thrust_m_s2) && command.body_rate_rad_s.eigen().allFinite();
}

}  // namespace

const char* to_string(StepStatus status) {
  switch (status) {
    case StepStatus::Ok:
      return "ok";
    case StepStatus::CommandRejected:
      return "command rejected (non-finite): holding the last one";
  }
  return "unknown";
}

World::World(const WorldParams& params)
    : params_(validated(params)),
      dt_ns_(std::llround(1e9 / params.physics_rate_hz)),
      dt_s_(clock::ns_to_s(dt_ns_)),
      quadrotor_(params.uav),
      relative_sensor_(params.relative_sensor, params.physics_rate_hz,
                       static_cast<int>(params.ugvs.size()),
                       derive_seed(params.seed, kRelativeSensorStream)),
      odometry_sensor_(params.odometry, params.physics_rate_hz, params.ugvs_with_odometry(),
                       derive_seed(params.seed, kOdometryStream)),
      imu_sensor_(params.imu, params.imu_filter, params.speed_estimator, params.physics_rate_hz,
                  static_cast<int>(params.ugvs.size()), params.gravity_m_s2,
                  derive_seed(params.seed, kImuStream)) {
  for (const auto& ugv : params_.ugvs) patterns_.emplace_back(ugv.pattern);
  state_.ugv_count = static_cast<std::int32_t>(params_.ugvs.size());
  update_ugvs();
  place_uav_at_start();
  update_payload();
  update_sensors();
}

World::World(const WorldParams& params, const FirmwareUavParams& firmware_uav) : World(params) {
  firmware_uav.validate("firmware_uav", params_.physics_rate_hz);
  motor_uav_.emplace(firmware_uav, params_.physics_rate_hz, params_.gravity_m_s2,
                     derive_seed(params_.seed, kMotorUavStream));
  if (!state_.uav_contact.resting) motor_uav_->spin_up_to_hover(state_.uav, extra_mass_kg());
}

void World::place_uav_at_start() {
  const auto& initial = params_.uav_initial;
  if (initial.start_on_ugv >= 0) {
    const UgvState& ugv = state_.ugvs[initial.start_on_ugv];
    state_.uav.position_m = ugv.position_m;
    surfaces().start_resting(state_.uav_contact, initial.start_on_ugv, ugv.position_m.eigen(),
                             ugv.yaw_rad + initial.yaw_rad);
    surfaces().carry(state_.uav_contact, state_.uav);
  } else {
    state_.uav.position_m = Vec3(initial.position_m);
    state_.uav.attitude = Quat(yaw_quaternion(initial.yaw_rad));
    if (initial.position_m.z() <= 0.0) {
      surfaces().start_resting(state_.uav_contact, -1, initial.position_m, initial.yaw_rad);
      surfaces().carry(state_.uav_contact, state_.uav);
    }
  }
  state_.payload.attached = params_.payload.attached_at_start;
  if (!state_.uav_contact.resting) {
    // Starting in mid-air is a test/benchmark convenience: start spun up to hover so that
    // the hover command holds the UAV still from the first step.
    state_.uav.thrust_n = (params_.uav.mass_true_kg + extra_mass_kg()) * params_.gravity_m_s2;
  }
}

StepStatus World::step(const QuadrotorCommand& command) {
  StepStatus status = StepStatus::Ok;
  if (is_finite(command)) {
    state_.last_command = command;
  } else {
    status = StepStatus::CommandRejected;
  }
  ++state_.step_index;
  // time from the step count, not by summing dt: no drift over long missions
  // Time from whole nanoseconds: it crosses the wire as stamp_ns and back unchanged.
  state_.time_s = clock::ns_to_s(static_cast<std::int64_t>(state_.step_index) * dt_ns_);
  update_ugvs();
  update_uav(state_.last_command);
  update_payload();
  update_sensors();
  return status;
}

StepStatus World::advance(const QuadrotorCommand& command, double duration_s) {
  StepStatus status = StepStatus::Ok;
  if (!std::isfinite(duration_s) || duration_s <= 0.0) return status;
  const auto steps = static_cast<std::uint64_t>(std::llround(duration_s / dt_s_));
  for (std::uint64_t i = 0; i < steps; ++i) {
    if (step(command) != StepStatus::Ok) status = StepStatus::CommandRejected;
  }
  return status;
}

void World::step(const MotorOutputs& outputs) {
  ++state_.step_index;
  state_.time_s = clock::ns_to_s(static_cast<std::int64_t>(state_.step_index) * dt_ns_);
  update_ugvs();
  if (settling_) motor_uav_->forget_motion();
  settling_ = false;
  motor_uav_->command(outputs);
  motor_uav_->step(state_.uav, state_.uav_contact, surfaces(), extra_mass_kg());
  // What the plant holds, in the rate model's terms: the rotors' thrust per unit mass.
  state_.last_command.thrust_m_s2 = state_.uav.thrust_n / (motor_uav_->mass_kg() + extra_mass_kg());
  update_payload();
  update_sensors();
}

void World::settle_uav(const MotorOutputs& outputs) {
  std::array<UgvState, kMaxUgvs> still = state_.ugvs;
  for (int k = 0; k < state_.ugv_count; ++k) {
    still[k].velocity_m_s = Vec3(0.0, 0.0, 0.0);
    still[k].acceleration_m_s2 = Vec3(0.0, 0.0, 0.0);
    still[k].yaw_rate_rad_s = 0.0;
    still[k].yaw_acceleration_rad_s2 = 0.0;
  }
  settling_ = true;
  motor_uav_->command(outputs);
  motor_uav_->step(state_.uav, state_.uav_contact,
                   SurfaceContact(still, state_.ugv_count, params_.ugvs), extra_mass_kg());
  update_payload();
}

bool World::release_payload() {
  PayloadState& payload = state_.payload;
  if (!payload.attached) return false;
  payload.attached = false;
  payload.released = true;
  payload.release_time_s = state_.time_s;
  payload.release_position_m = state_.uav.position_m;
  for (int k = 0; k < state_.ugv_count; ++k) {
    payload.release_position_in_ugv_m[k] =
        Vec3(state_.ugvs[k].to_body(state_.uav.position_m.eigen()));
  }
  payload.position_m = state_.uav.position_m;
  payload.velocity_m_s = state_.uav.velocity_m_s;
  return true;
}

RelativeState World::true_relative_state(int ugv_index) const {
  return cover::sim::true_relative_state(state_.uav, state_.ugvs[ugv_index], state_.time_s);
}

double World::hover_thrust_command_m_s2() const {
  return quadrotor_.hover_thrust_command_m_s2(extra_mass_kg(), params_.gravity_m_s2);
}

double World::extra_mass_kg() const {
  return state_.payload.attached ? params_.payload.mass_kg : 0.0;
}

void World::update_ugvs() {
  for (int k = 0; k < state_.ugv_count; ++k) {
    const UgvKinematics kin = patterns_[k].at(state_.time_s);
    UgvState& ugv = state_.ugvs[k];
    ugv.position_m = Vec3(kin.position_m.x(), kin.position_m.y(), params_.ugvs[k].deck_height_m);
    ugv.velocity_m_s = Vec3(kin.velocity_m_s.x(), kin.velocity_m_s.y(), 0.0);
    ugv.acceleration_m_s2 = Vec3(kin.acceleration_m_s2.x(), kin.acceleration_m_s2.y(), 0.0);
    ugv.yaw_rad = kin.yaw_rad;
    ugv.yaw_rate_rad_s = kin.yaw_rate_rad_s;
    ugv.yaw_acceleration_rad_s2 = kin.yaw_acceleration_rad_s2;
  }
}

SurfaceContact World::surfaces() const {
  return SurfaceContact(state_.ugvs, state_.ugv_count, params_.ugvs);
}

void World::update_uav(const QuadrotorCommand& command) {
  const double mass_kg = params_.uav.mass_true_kg + extra_mass_kg();
  quadrotor_.step(state_.uav, command, extra_mass_kg(), params_.gravity_m_s2, dt_s_);
  surfaces().resolve(state_.uav, state_.uav_contact, mass_kg, params_.gravity_m_s2);
}

void World::update_payload() {
  PayloadState& payload = state_.payload;
  if (payload.attached || !payload.released) {
    // Hanging under the UAV (or never carried): it moves with the UAV.
    payload.position_m = state_.uav.position_m;
    payload.velocity_m_s = state_.uav.velocity_m_s;
    return;
  }
  ContactState& contact = payload.contact;
  if (contact.resting) {
    const SurfaceContact contact_surfaces = surfaces();
    const Eigen::Vector3d position =
        contact_surfaces.to_world(contact.surface, contact.offset_in_surface_m.eigen());
    payload.position_m = Vec3(position);
    payload.velocity_m_s = Vec3(contact_surfaces.point_velocity_m_s(contact.surface, position));
    return;
  }
  // Free fall (a dense parcel: drag neglected); exact for constant gravity.
  const double g = params_.gravity_m_s2;
  Eigen::Vector3d position = payload.position_m.eigen();
  Eigen::Vector3d velocity = payload.velocity_m_s.eigen();
  position += velocity * dt_s_ - Eigen::Vector3d(0, 0, 0.5 * g * dt_s_ * dt_s_);
  velocity.z() -= g * dt_s_;
  payload.position_m = Vec3(position);
  payload.velocity_m_s = Vec3(velocity);
  const SurfaceContact contact_surfaces = surfaces();
  const SurfaceContact::Hit hit = contact_surfaces.penetrated(position);
  if (hit.hit) {
    contact_surfaces.start_resting(contact, hit.surface, position, 0.0);
    payload.position_m =
        Vec3(contact_surfaces.to_world(hit.surface, contact.offset_in_surface_m.eigen()));
    payload.velocity_m_s =
        Vec3(contact_surfaces.point_velocity_m_s(hit.surface, payload.position_m.eigen()));
  }
}

void World::update_sensors() {
  relative_sensor_.update(state_);
  odometry_sensor_.update(state_);
  imu_sensor_.update(state_, odometry_sensor_);
}

}  // namespace cover::sim
