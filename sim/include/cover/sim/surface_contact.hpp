#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "cover/sim/world_params.hpp"
#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

// The ground (z = 0) and every UGV's deck (a rectangle at deck height, moving with its UGV)
// as rigid, perfectly inelastic surfaces, for any plant that fills a QuadrotorState (the
// rate model and the motor-level quadrotor alike). A body touching one without the thrust
// to lift off (vertical T / m <= g) rests on it: levelled, carried along at its contact
// point (full friction), yaw carried with the surface; it lifts off as soon as T / m > g.
// Side impacts with a UGV body are not modelled: a body entering a deck's footprint below
// the deck top is put on top of it.
//
// A view: it holds references to the UGVs' current states and deck footprints, so build
// one after the UGVs have moved, and do not keep it past them.
class SurfaceContact {
 public:
  struct Hit {
    bool hit = false;
    std::int32_t surface = -1;  // -1 ground, k deck of UGV k
  };

  // The decks of ugv_states[0, ugv_count), with the footprints of `ugv_params` (same order).
  SurfaceContact(const std::array<UgvState, kMaxUgvs>& ugv_states, int ugv_count,
                 const std::vector<UgvParams>& ugv_params);

  // The first surface `point_m` is below (inside a deck's footprint, or under the ground).
  Hit penetrated(const Eigen::Vector3d& point_m) const;
  double height_m(std::int32_t surface) const;
  double yaw_rad(std::int32_t surface) const;
  double yaw_rate_rad_s(std::int32_t surface) const;
  Eigen::Vector3d point_velocity_m_s(std::int32_t surface, const Eigen::Vector3d& point_m) const;
  Eigen::Vector3d to_world(std::int32_t surface, const Eigen::Vector3d& offset_m) const;
  Eigen::Vector3d to_surface(std::int32_t surface, const Eigen::Vector3d& point_m) const;

  // Starts resting on `surface` at `point_m` (put on its top) with world yaw `yaw_rad`.
  void start_resting(ContactState& contact, std::int32_t surface, const Eigen::Vector3d& point_m,
                     double yaw_rad) const;
  // A resting body is carried by its surface: pose and velocity of its contact point,
  // levelled (the landing gear settles it flat), body rate the surface's yaw rate.
  void carry(const ContactState& contact, QuadrotorState& body) const;
  // After a free-flight step of a body of `mass_kg` whose `thrust_n` is its collective
  // thrust: keeps it resting, lets it lift off, or lands it on what it penetrated.
  void resolve(QuadrotorState& body, ContactState& contact, double mass_kg,
               double gravity_m_s2) const;

 private:
  const std::array<UgvState, kMaxUgvs>& ugv_states_;
  int ugv_count_;
  const std::vector<UgvParams>& ugv_params_;
};

}  // namespace cover::sim
