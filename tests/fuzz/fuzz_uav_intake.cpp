// The UAV agent's sample intake (cover-uav-agent's DdsUavInputs): relative states and UGV
// IMU samples with NaN, infinities, huge values, foreign ids and stale or future stamps,
// interleaved with clock steps (forwards, backwards, non-finite), through the same checks
// (wire/intake.hpp) and slots the agent uses, then the failsafe ladder's assessment.
// Contract: what the loop receives is finite, in range, addressed to this UAV and UGV,
// never stamped beyond the clock's tolerance when taken, never older than what it got
// before; a state the ladder calls usable is one of those.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "cover/mission/failsafe_ladder.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/wire/eigen.hpp"
#include "cover/wire/intake.hpp"
#include "cover/wire/sensors.hpp"
#include "cover/wire/ugv_imu_measurement.hpp"
#include "fuzz_input.hpp"

namespace {

using cover::fuzz::FuzzInput;
using cover::fuzz::require;
namespace msg = cover::msg;
namespace wire = cover::wire;

constexpr std::uint32_t kUav = 1;
constexpr std::uint32_t kUgv = 0;

std::uint32_t id(FuzzInput& in, std::uint32_t expected) {
  switch (in.byte() % 8) {
    case 0:
      return expected + 1;
    case 1:
      return in.raw<std::uint32_t>();
    default:
      return expected;
  }
}

msg::Vector3 vec(FuzzInput& in) {
  return {in.real(), in.real(), in.real()};
}

std::int64_t stamp(FuzzInput& in, double now_s) {
  // Offsets from a clock within +-30 years (a hostile stamp of any value comes from case 0).
  const std::int64_t now_ns =
      wire::to_stamp_ns(std::isfinite(now_s) ? std::clamp(now_s, -1e9, 1e9) : 0.0);
  switch (in.byte() % 8) {
    case 0:
      return in.raw<std::int64_t>();  // anything, INT64_MIN..MAX
    case 1:
      return now_ns + 3'600'000'000'000LL;  // an hour ahead
    case 2:
      return now_ns - in.range(0, 10'000'000'000LL);  // up to 10 s old
    default:
      return now_ns + in.range(-20'000'000, 20'000'000);  // within +-20 ms of a finite clock
  }
}

msg::RelativeState relative_state(FuzzInput& in, double now_s) {
  msg::RelativeState s;
  s.uav_id = id(in, kUav);
  s.ugv_id = id(in, kUgv);
  s.stamp_ns = stamp(in, now_s);
  s.position_m = vec(in);
  s.velocity_m_s = vec(in);
  if (in.byte() % 2) {
    s.attitude = {in.real(), in.real(), in.real(), in.real()};
  } else {
    s.attitude = {1.0, 0.0, 0.0, 0.0};
  }
  s.valid = in.byte() % 8 != 0;
  s.position_std_m = in.byte() % 4 ? 0.01 : in.real();
  return s;
}

msg::UgvImu ugv_imu(FuzzInput& in, double now_s) {
  msg::UgvImu s;
  s.ugv_id = id(in, kUgv);
  s.stamp_ns = stamp(in, now_s);
  s.seq = in.raw<std::uint32_t>();
  s.specific_force_m_s2 = vec(in);
  s.angular_velocity_rad_s = vec(in);
  s.angular_acceleration_rad_s2 = vec(in);
  s.speed_m_s = in.real();
  s.speed_source = static_cast<msg::SpeedSource>(in.byte() % 5);
  return s;
}

void check_state(const msg::RelativeState& s, double now_s, const wire::IntakeLimits& limits) {
  require(s.uav_id == kUav && s.ugv_id == kUgv, "a foreign relative state got through");
  const auto state = wire::from_msg(s);
  if (!state) return;  // marked lost: the loop treats it as missing
  require(state->position_m.allFinite() && state->velocity_m_s.allFinite() &&
              state->attitude.coeffs().allFinite() && std::isfinite(state->stamp_s),
          "a non-finite relative state got through");
  require(state->position_m.norm() <= limits.max_position_m &&
              state->velocity_m_s.norm() <= limits.max_speed_m_s &&
              std::abs(state->attitude.norm() - 1.0) <= limits.attitude_norm_tolerance,
          "an out-of-range relative state got through");
}

void check_imu(const msg::UgvImu& s, const wire::IntakeLimits& limits) {
  require(s.ugv_id == kUgv, "a foreign IMU sample got through");
  const auto imu = wire::from_msg(s);
  require(imu.motion.specific_force_m_s2.allFinite() &&
              imu.motion.angular_velocity_rad_s.allFinite() &&
              imu.motion.angular_acceleration_rad_s2.allFinite() &&
              std::isfinite(imu.motion.speed_m_s) && std::isfinite(imu.stamp_s),
          "a non-finite IMU sample got through");
  require(imu.motion.specific_force_m_s2.norm() <= limits.max_specific_force_m_s2 &&
              imu.motion.angular_velocity_rad_s.norm() <= limits.max_angular_velocity_rad_s,
          "an out-of-range IMU sample got through");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  const wire::IntakeLimits limits;
  const cover::mission::MissionParams mission;
  wire::SampleSlot<msg::RelativeState> states;
  wire::SampleSlot<msg::UgvImu> imus;
  wire::RejectionCounts counts;
  std::optional<double> now_s;
  std::int64_t last_state_ns = std::numeric_limits<std::int64_t>::min();
  std::int64_t last_imu_ns = std::numeric_limits<std::int64_t>::min();
  std::uint64_t offered = 0;
  while (!in.empty()) {
    const double clock_s = now_s.value_or(0.0);
    switch (in.byte() % 4) {
      case 0: {
        const msg::RelativeState s = relative_state(in, clock_s);
        ++offered;
        if (const auto why = wire::check_content(s, kUav, kUgv, limits)) {
          counts.add(*why);
        } else {
          states.offer(s);
        }
        break;
      }
      case 1: {
        const msg::UgvImu s = ugv_imu(in, clock_s);
        ++offered;
        if (const auto why = wire::check_content(s, kUgv, limits)) {
          counts.add(*why);
        } else {
          imus.offer(s);
        }
        break;
      }
      case 2:  // the clock: forwards a step, a jump, or anything at all
        now_s = in.byte() % 4 ? clock_s + 0.01 : in.real();
        break;
      default: {  // a control step pulls both inputs
        if (const auto why = states.settle(now_s, limits)) counts.add(*why);
        if (const auto why = imus.settle(now_s, limits)) counts.add(*why);
        cover::mission::LadderInput ladder;
        std::optional<cover::model::RelativeState> state;
        cover::mission::UgvImuMeasurement imu;
        if (const auto& s = states.accepted()) {
          check_state(*s, clock_s, limits);
          require(s->stamp_ns >= last_state_ns, "relative states went back in time");
          last_state_ns = s->stamp_ns;
          state = wire::from_msg(*s);
        }
        if (const auto& s = imus.accepted()) {
          check_imu(*s, limits);
          require(s->stamp_ns >= last_imu_ns, "IMU samples went back in time");
          last_imu_ns = s->stamp_ns;
          imu = wire::from_msg(*s);
          ladder.has_imu = true;
          ladder.imu = &imu.motion;
          ladder.imu_stamp_s = imu.stamp_s;
        }
        ladder.has_state = state.has_value();
        ladder.state = state ? &*state : nullptr;
        const auto health = cover::mission::assess_inputs(ladder, now_s.value_or(0.0), mission);
        require(std::isfinite(health.age_s), "the ladder's input age is not finite");
        require(!health.state_usable || state.has_value(), "the ladder used a missing state");
        break;
      }
    }
  }
  require(counts.total() <= offered, "more rejections than samples");
  return 0;
}
