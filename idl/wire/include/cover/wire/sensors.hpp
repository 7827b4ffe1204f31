#pragma once

#include <cstdint>
#include <optional>

#include "cover/msg/types.hpp"
#include "cover/vocabulary/relative_state.hpp"
#include "cover/vocabulary/speed_estimate.hpp"
#include "cover/vocabulary/ugv_imu.hpp"

namespace cover::wire {

// Relative state of UAV `uav_id` in G_`ugv_id`.
msg::RelativeState to_msg(const model::RelativeState& state, std::uint32_t uav_id,
                          std::uint32_t ugv_id, double position_std_m = 0.0);
// nullopt when the sender marked the state invalid (its estimator lost the UGV).
std::optional<model::RelativeState> from_msg(const msg::RelativeState& state);

// The UGV agent's filtered IMU (a, Omega, beta in G_k) and its forward speed estimate.
msg::UgvImu to_msg(const ugv::FilteredImu& imu, const ugv::SpeedEstimate& speed,
                   std::uint32_t ugv_id, std::uint32_t seq);
// The UAV side's reading of it: wire/ugv_imu_measurement.hpp.

}  // namespace cover::wire
