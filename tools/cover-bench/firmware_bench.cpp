// cover-bench firmware: cover-fc-bridge against the real autopilot firmware (PX4 SITL with
// its SIH physics, ArduCopter SITL), found through COVER_PX4_SITL / COVER_ARDUPILOT_SITL
// (docs/flight-controller.md, "The real firmware in the loop"). Per autopilot, one fresh
// firmware instance flown from COVER's commands (sim/firmware's FirmwareRig: the real bridge
// process, the agent's UavCommand stream on DDS, a LinkTap on the companion link, a ground
// station's MAVLink link of the benchmark's own):
//  setpoints: SET_ATTITUDE_TARGET frames the tap passes to the firmware per second (1 s
//             windows over a hold: median and the worst window);
//  latency:   the agent's command -> its setpoint at the firmware's socket (the tap), and ->
//             the firmware's ATTITUDE_TARGET carrying it (its own report of its setpoint, on
//             the ground-station link at the rate the firmware grants). Each command of a
//             yaw-rate staircase is identifiable by its value;
//  hover:     the bridge's hover-thrust estimate (cover/uav/0/fc) once settled vs the
//             firmware's own hover thrust;
//  step:      a roll-rate step as the firmware flew it (ATTITUDE_QUATERNION rollspeed): rise
//             time to 90 %, overshoot, steady error;
//  faults:    agent killed (its last command -> the bridge's land command on the link, target
//             <= 150 ms; the firmware's land mode), link cut both ways (heartbeat loss: when
//             the bridge says the link is lost, when the firmware's own failsafe acts),
//             bridge killed (SIGKILL: the firmware's own offboard-loss failsafe, against
//             COM_OF_LOSS_T / GUID_TIMEOUT). --tries each, median and worst.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/clock/clock.hpp"
#include "cover/firmware/agent_flight.hpp"
#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/firmware_profile.hpp"
#include "cover/firmware/firmware_rig.hpp"
#include "cover/firmware/hover_settle.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "cover_binary.hpp"
#include "not_measured.hpp"

namespace {

namespace fw = cover::firmware;
namespace mav = cover::mavlink;
using namespace std::chrono_literals;
using cover::bench::figure_json;
using cover::bench::figure_text;
using cover::bench::percentile;

constexpr auto kBoot = 120s;             // start to "would arm": boot, estimator, GPS fix
constexpr double kFlightHeight_m = 3.0;  // above where it took off
constexpr double kLandTarget_ms = 150.0;
constexpr double kStepRate_rad_s = 0.5;
constexpr auto kStepDuration = 400ms;
constexpr double kTurnRate_rad_s = 0.5;  // flown while a failsafe is awaited: its end shows
// The yaw-rate staircase: each step's value differs from the last, signs alternate so the
// heading comes back; a step lasts long enough for a 10 Hz report to carry it.
constexpr auto kStairStep = 200ms;
constexpr double kStairTolerance_rad_s = 1e-4;

std::int64_t now_ns() {
  return cover::clock::monotonic_ns();
}
double ms(std::int64_t from_ns, std::int64_t to_ns) {
  return static_cast<double>(to_ns - from_ns) * 1e-6;
}
double median(const std::vector<double>& v) {
  return percentile(v, 0.5);
}
double worst(const std::vector<double>& v) {
  return percentile(v, 1.0);
}

// Flies the agent's current policy for `duration` (the benchmark's phase length, not a wait
// for something to happen).
void fly_for(std::chrono::milliseconds duration) {
  std::this_thread::sleep_for(duration);
}

bool wait_for(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= end) return condition();
    std::this_thread::sleep_for(5ms);  // polling a condition with a deadline
  }
  return true;
}

bool monitor_sees(fw::FirmwareRig& rig, const std::function<bool(const mav::Heartbeat&)>& what) {
  const auto hb = rig.monitor().heartbeat();
  return hb && what(*hb);
}

bool flying_for_cover(fw::FirmwareRig& rig) {
  const cover::Autopilot kind = rig.firmware_kind();
  return monitor_sees(rig, [&](auto& hb) { return fw::in_offboard(kind, hb) && fw::armed(hb); });
}

// A step the benchmark could not take: what and why, for the report.
struct Failed {
  std::string what;
};

void require(bool ok, const std::string& what) {
  if (!ok) throw Failed{what};
}

// After a phase: the firmware still flies COVER's setpoints, or the phase measured
// something else (a loaded machine can starve the agent past the bridge's cmd_timeout_s,
// and the bridge lands the UAV): the bridge's reason is named.
void still_flying(fw::FirmwareRig& rig, const std::string& phase) {
  if (flying_for_cover(rig)) return;
  const auto state = rig.state();
  throw Failed{"the firmware left offboard during the " + phase +
               (state && !state->failsafe.empty() ? " (bridge: " + state->failsafe + ")" : "")};
}

// --- the flight ---------------------------------------------------------------------------

// The operator's start (docs/flight-controller.md): the agent streams motors-off, then
// `cover fc offboard 0` and `cover fc arm 0`, each answered by the firmware; the agent
// climbs to kFlightHeight_m. The height held.
double arm_and_take_off(fw::FirmwareRig& rig) {
  const cover::Autopilot kind = rig.firmware_kind();
  require(rig.connect_monitor(60s), "the monitor's streams");
  // The firmware's own setpoint report and its rates at 100 Hz (it may grant less).
  rig.monitor().request_stream(mav::AttitudeTarget::kId, 100.0);
  rig.monitor().request_stream(mav::AttitudeQuaternion::kId, 100.0);
  require(wait_for(
              [&] {
                const auto s = rig.state();
                return s && s->link_ok && s->system_id != 0;
              },
              30s),
          "the bridge's link to the firmware");
  rig.agent_flies([] { return fw::motors_off(); });
  require(wait_for([&] { return rig.ready_to_arm(); }, kBoot), "the firmware would not arm");
  require(wait_for(
              [&] {
                const auto s = rig.state();
                return rig.agent_written() >= 150 && s && s->setpoint_rate_hz > 80.0;
              },
              10s),
          "the agent's stream at the bridge");
  require(rig.cover_fc({"offboard", "0"}).exit_code == 0, "cover fc offboard 0");
  require(
      wait_for(
          [&] { return monitor_sees(rig, [&](auto& hb) { return fw::in_offboard(kind, hb); }); },
          5s),
      "the firmware in offboard");
  require(rig.cover_fc({"arm", "0"}).exit_code == 0, "cover fc arm 0");
  require(wait_for([&] { return monitor_sees(rig, [](auto& hb) { return fw::armed(hb); }); }, 5s),
          "the firmware armed");
  auto& monitor = rig.monitor();
  const double height = fw::height_m(monitor.position()->value) + kFlightHeight_m;
  rig.agent_flies(fw::hold_height(monitor, height));
  require(wait_for(
              [&] {
                const auto p = monitor.position();
                return p && std::abs(fw::height_m(p->value) - height) < 0.3 &&
                       std::abs(p->value.vz) < 0.3;
              },
              30s),
          "the climb to " + std::to_string(kFlightHeight_m) + " m");
  return height;
}

// The operator gives the UAV back to COVER in flight (after a fault): the agent streams its
// height hold, `cover fc offboard 0`, the UAV climbs back to `height`.
void take_back(fw::FirmwareRig& rig, double height) {
  auto& monitor = rig.monitor();
  rig.agent_flies(fw::hold_height(monitor, height));
  require(wait_for(
              [&] {
                const auto s = rig.state();
                return rig.agent_written() >= 110 && s && s->link_ok && s->setpoint_rate_hz > 80.0;
              },
              10s),
          "the agent's stream at the bridge after the fault");
  // The bridge refuses while a mode change of its own awaits an answer (its blind land
  // request of a link cut, answered once the link is back): "try again", as an operator does.
  bool offboard = false;
  for (int attempt = 0; attempt < 5 && !offboard; ++attempt) {
    offboard = rig.cover_fc({"offboard", "0"}).exit_code == 0;
  }
  require(offboard, "cover fc offboard 0 after the fault");
  require(wait_for([&] { return flying_for_cover(rig); }, 5s), "offboard again after the fault");
  require(wait_for(
              [&] {
                const auto p = monitor.position();
                return p && std::abs(fw::height_m(p->value) - height) < 0.5;
              },
              20s),
          "back at the height after the fault");
}

// --- setpoint rate and latency --------------------------------------------------------------

struct Stair {
  std::mutex mutex;
  std::vector<std::pair<double, std::int64_t>> steps;  // FLU yaw rate, first computed at
};

struct RateAndLatency {
  std::vector<double> window_hz;       // setpoints per 1 s window
  std::vector<double> to_firmware_ms;  // command -> setpoint at the firmware's socket
  std::vector<double> echo_ms;         // command -> the firmware's ATTITUDE_TARGET carrying it
  double echo_rate_hz = NAN;
  std::size_t steps = 0;
  std::string echo_note;  // why an echo was not matched, when none was
};

// The height hold with a yaw-rate staircase added; every step's value and the time the
// agent first computed it are logged.
fw::AgentStream::Policy staircase(const fw::FirmwareMonitor& monitor, double height,
                                  std::shared_ptr<Stair> stair) {
  const std::int64_t start = now_ns();
  const std::int64_t step_ns = std::chrono::nanoseconds(kStairStep).count();
  return [&monitor, height, stair, start, step_ns] {
    const std::int64_t k = (now_ns() - start) / step_ns;
    const double value = (k % 2 == 0 ? 1.0 : -1.0) * (0.05 + 0.01 * static_cast<double>(k % 4));
    fw::AgentSetpoint extra;
    extra.yaw_rate = value;
    {
      std::lock_guard<std::mutex> lock(stair->mutex);
      if (stair->steps.size() == static_cast<std::size_t>(k))
        stair->steps.push_back({value, now_ns()});
    }
    return fw::hold_height(monitor, height, extra)();
  };
}

RateAndLatency rate_and_latency(fw::FirmwareRig& rig, double height, std::chrono::seconds hold) {
  auto stair = std::make_shared<Stair>();
  const std::int64_t from = now_ns();
  rig.agent_flies(staircase(rig.monitor(), height, stair));
  fly_for(hold);
  const std::int64_t to = now_ns();
  rig.agent_flies(fw::hold_height(rig.monitor(), height));
  RateAndLatency out;
  const auto setpoints = rig.tap().setpoints_since(from);
  for (std::int64_t w = from; w + 1'000'000'000 <= to; w += 1'000'000'000) {
    double n = 0;
    for (const auto& s : setpoints) n += s.at_ns >= w && s.at_ns < w + 1'000'000'000 ? 1 : 0;
    out.window_hz.push_back(n);
  }
  const auto echoes = rig.monitor().attitude_targets_since(from);
  out.echo_rate_hz = rig.monitor().rate_hz(mav::AttitudeTarget::kId, from, to);
  std::vector<std::pair<double, std::int64_t>> steps;
  {
    std::lock_guard<std::mutex> lock(stair->mutex);
    steps = stair->steps;
  }
  out.steps = steps.size();
  double nearest_echo = NAN;  // the closest an echo came to a step's value (FRD), for a note
  for (std::size_t i = 1; i + 1 < steps.size(); ++i) {
    const double frd = -steps[i].first;  // the bridge sends FRD: yaw negated
    const std::int64_t at = steps[i].second;
    const std::int64_t next = steps[i + 1].second;
    for (const auto& s : setpoints) {
      if (s.at_ns >= at && std::abs(s.value.body_yaw_rate - frd) < kStairTolerance_rad_s) {
        out.to_firmware_ms.push_back(ms(at, s.at_ns));
        break;
      }
    }
    for (const auto& e : echoes) {
      if (e.at_ns < at || e.at_ns > next + 500'000'000) continue;
      const double off = std::abs(e.value.body_yaw_rate - frd);
      if (!std::isfinite(nearest_echo) || off < nearest_echo) nearest_echo = off;
      if (off < kStairTolerance_rad_s) {
        out.echo_ms.push_back(ms(at, e.at_ns));
        break;
      }
    }
  }
  if (out.echo_ms.empty()) {
    out.echo_note = echoes.empty()
                        ? "the firmware sent no ATTITUDE_TARGET on the ground-station link"
                        : "no ATTITUDE_TARGET carried a step's yaw rate (closest " +
                              figure_text("%.4f rad/s", nearest_echo) + " off, " +
                              std::to_string(echoes.size()) + " reports)";
  }
  return out;
}

// --- hover thrust ----------------------------------------------------------------------------

// The hover thrust the firmware's own motion gives on `thrust`: the specific force along it
// is g + a_up = g thrust / hover, a_up the least-squares slope of its vertical speed.
double hover_from_motion(const std::vector<fw::Timed<mav::LocalPositionNed>>& window,
                         double thrust) {
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  for (const auto& p : window) {
    const double t = static_cast<double>(p.at_ns - window.front().at_ns) * 1e-9;
    const double v_up = -p.value.vz;
    n += 1;
    st += t;
    sv += v_up;
    stt += t * t;
    stv += t * v_up;
  }
  if (n < 10) return NAN;
  const double a_up = (n * stv - st * sv) / (n * stt - st * st);
  return thrust * fw::kGravity_m_s2 / (fw::kGravity_m_s2 + a_up);
}

struct Hover {
  double estimate = NAN;
  double truth = NAN;
  std::string truth_source;
  double error_percent = NAN;
  double settle_s = NAN;  // airborne -> settled
};

Hover hover_estimate(fw::FirmwareRig& rig, double before, std::int64_t airborne_ns) {
  Hover h;
  const cover::Autopilot kind = rig.firmware_kind();
  if (!wait_for([&] { return fw::hover_estimate_settled(rig, airborne_ns, now_ns()); }, 45s)) {
    h.truth_source = "the bridge's estimate did not settle in 45 s";
    return h;
  }
  h.settle_s = ms(airborne_ns, now_ns()) * 1e-3;
  // Thrust g, zero rates, for 5 s: the estimate alone holds the height.
  rig.agent_flies([] { return fw::hover(); });
  const std::int64_t from = now_ns();
  fly_for(5s);
  const auto state = rig.state();
  const auto sent = rig.tap().last_setpoint();
  h.estimate = state ? state->hover_thrust : NAN;
  const auto after = fw::firmware_hover_thrust(kind, rig.monitor());
  if (kind == cover::Autopilot::Px4) {
    h.truth = after.value_or(NAN);
    h.truth_source = "SIH_MASS g / (4 SIH_T_MAX)";
  } else if (after && std::abs(*after - before) > 1e-4) {
    h.truth = *after;
    h.truth_source = "MOT_THST_HOVER as ArduCopter learned it";
  } else if (sent) {
    // ArduCopter learns MOT_THST_HOVER only under its own altitude control.
    h.truth = hover_from_motion(rig.monitor().positions_since(from), sent->value.thrust);
    h.truth_source = "its vertical acceleration on the thrust sent (MOT_THST_HOVER not learned)";
  }
  h.error_percent = 100.0 * std::abs(h.estimate - h.truth) / h.truth;
  return h;
}

// --- rate step -------------------------------------------------------------------------------

struct Step {
  double rise_90_ms = NAN;
  double overshoot_percent = NAN;
  double steady_error_rad_s = NAN;
  double report_hz = NAN;
};

// A roll-rate step of kStepRate_rad_s for kStepDuration, then the same back (level again),
// from a level hold; the firmware's ATTITUDE_QUATERNION rollspeed over the first half.
Step rate_step(fw::FirmwareRig& rig, double height) {
  auto& monitor = rig.monitor();
  rig.agent_flies(fw::hold_height(monitor, height));
  fly_for(1500ms);
  auto started = std::make_shared<std::int64_t>(0);
  auto mutex = std::make_shared<std::mutex>();
  // The step starts at the agent's first command at or after t0 (the doublet would fly it
  // from its first call on); until then the level hold.
  const std::int64_t t0 = now_ns() + 50'000'000;
  const auto level = fw::hold_height(monitor, height);
  const auto doublet =
      fw::roll_rate_doublet(monitor, height, t0, kStepRate_rad_s, kStepDuration, 0ms);
  rig.agent_flies([level, doublet, started, mutex, t0] {
    const std::int64_t now = now_ns();
    if (now < t0) return level();
    {
      std::lock_guard<std::mutex> lock(*mutex);
      if (*started == 0) *started = now;
    }
    return doublet();
  });
  fly_for(1500ms);
  rig.agent_flies(fw::hold_height(monitor, height));
  std::int64_t start = 0;
  {
    std::lock_guard<std::mutex> lock(*mutex);
    start = *started;
  }
  Step s;
  const std::int64_t step_ns = std::chrono::nanoseconds(kStepDuration).count();
  const auto attitudes = monitor.attitudes_since(start);
  s.report_hz = monitor.rate_hz(mav::AttitudeQuaternion::kId, start, start + step_ns);
  double peak = -1e9, tail_sum = 0, tail_n = 0;
  for (const auto& a : attitudes) {
    const std::int64_t t = a.at_ns - start;
    if (t > step_ns) break;
    const double rate = a.value.rollspeed;
    if (!std::isfinite(s.rise_90_ms) && rate >= 0.9 * kStepRate_rad_s) s.rise_90_ms = t * 1e-6;
    peak = std::max(peak, rate);
    if (t >= step_ns - 150'000'000) {
      tail_sum += rate;
      tail_n += 1;
    }
  }
  if (peak > -1e9)
    s.overshoot_percent = 100.0 * std::max(0.0, peak - kStepRate_rad_s) / kStepRate_rad_s;
  if (tail_n > 0) s.steady_error_rad_s = std::abs(tail_sum / tail_n - kStepRate_rad_s);
  return s;
}

// --- faults ----------------------------------------------------------------------------------

struct FaultTry {
  nlohmann::json row;
  double headline = NAN;  // the figure the table shows
};

// When the firmware's own failsafe took over after `from_ns`: PX4 says so ("Failsafe"), then
// turns the yaw rate down; ArduCopter says nothing and stops the yaw rate at once. NaN when
// neither within `timeout`.
double failsafe_after_s(fw::FirmwareRig& rig, std::int64_t from_ns,
                        std::chrono::milliseconds timeout) {
  std::optional<std::int64_t> at;
  wait_for(
      [&] {
        if (rig.firmware_kind() == cover::Autopilot::Px4) {
          // Its "Failsafe activated" text, or its HEARTBEAT in its land mode, whichever comes
          // first: a STATUSTEXT can be dropped on a loaded machine (CI: none within 7 s).
          for (const auto& t : rig.monitor().texts()) {
            if (t.at_ns >= from_ns && t.value.find("Failsafe") != std::string::npos) {
              at = t.at_ns;
              break;
            }
          }
          for (const auto& hb : rig.monitor().heartbeats_since(from_ns)) {
            if (fw::in_land(cover::Autopilot::Px4, hb.value)) {
              if (!at || hb.at_ns < *at) at = hb.at_ns;
              break;
            }
          }
          return at.has_value();
        }
        // The first moment from which the yaw rate stays below 70 % of the turn for 100 ms
        // (one low sample of a noisy rate loop is no failsafe).
        std::optional<std::int64_t> below_since;
        for (const auto& a : rig.monitor().attitudes_since(from_ns)) {
          if (std::abs(a.value.yawspeed) >= 0.7 * kTurnRate_rad_s) {
            below_since.reset();
          } else if (!below_since) {
            below_since = a.at_ns;
          } else if (a.at_ns - *below_since >= 100'000'000) {
            at = below_since;
            return true;
          }
        }
        return false;
      },
      timeout);
  return at ? ms(from_ns, *at) * 1e-3 : NAN;
}

// The first HEARTBEAT after `from_ns` that says `what`, s after it.
double mode_after_s(fw::FirmwareRig& rig, std::int64_t from_ns,
                    const std::function<bool(const mav::Heartbeat&)>& what,
                    std::chrono::milliseconds timeout) {
  std::optional<std::int64_t> at;
  wait_for(
      [&] {
        for (const auto& hb : rig.monitor().heartbeats_since(from_ns)) {
          if (what(hb.value)) {
            at = hb.at_ns;
            return true;
          }
        }
        return false;
      },
      timeout);
  return at ? ms(from_ns, *at) * 1e-3 : NAN;
}

// The firmware's yaw rate over the last half second, as the fault's detector reads it.
struct TurnWindow {
  std::size_t reports = 0;
  double mean_rad_s = NAN;
  double lowest_rad_s = NAN;
  bool dipped = false;  // a 100 ms stretch below 70 %: what a failsafe looks like
};

TurnWindow last_half_second_of_turn(fw::FirmwareRig& rig) {
  TurnWindow w;
  double sum = 0.0;
  std::optional<std::int64_t> below_since;
  for (const auto& a : rig.monitor().attitudes_since(now_ns() - 500'000'000)) {
    const double rate = std::abs(a.value.yawspeed);
    ++w.reports;
    sum += rate;
    w.lowest_rad_s = std::isfinite(w.lowest_rad_s) ? std::min(w.lowest_rad_s, rate) : rate;
    if (rate >= 0.7 * kTurnRate_rad_s) {
      below_since.reset();
    } else if (!below_since) {
      below_since = a.at_ns;
    } else if (a.at_ns - *below_since >= 100'000'000) {
      w.dipped = true;
    }
  }
  if (w.reports > 0) w.mean_rad_s = sum / static_cast<double>(w.reports);
  return w;
}

// Turns at kTurnRate_rad_s while holding the height, until the firmware has flown it for
// 0.5 s at 80 % of it on average, with no stretch the failsafe detector would take for the
// turn's end (single noisy reports of a loaded rate loop are not): the fault's effect is the
// turn's end. When it never does, the report says what the firmware flew instead.
void turn(fw::FirmwareRig& rig, double height) {
  fw::AgentSetpoint extra;
  extra.yaw_rate = kTurnRate_rad_s;
  rig.agent_flies(fw::hold_height(rig.monitor(), height, extra));
  TurnWindow last;
  const bool steady = wait_for(
      [&] {
        last = last_half_second_of_turn(rig);
        return last.reports >= 20 && !last.dipped && last.mean_rad_s >= 0.8 * kTurnRate_rad_s;
      },
      10s);
  if (steady) return;
  const auto hb = rig.monitor().heartbeat();
  throw Failed{
      "a steady turn before the fault: in the last 0.5 s " + std::to_string(last.reports) +
      " attitude reports, mean " + figure_text("%.3f", last.mean_rad_s) + " rad/s, lowest " +
      figure_text("%.3f", last.lowest_rad_s) + " rad/s of " + figure_text("%.2f", kTurnRate_rad_s) +
      (last.dipped ? ", a 100 ms dip" : "") + "; firmware " +
      (hb ? std::string(fw::armed(*hb) ? "armed" : "disarmed") +
                (fw::in_offboard(rig.firmware_kind(), *hb) ? ", COVER's mode" : ", another mode") +
                " (" + std::to_string(hb->custom_mode) + ")"
          : std::string("silent"))};
}

FaultTry agent_killed(fw::FirmwareRig& rig) {
  const cover::Autopilot kind = rig.firmware_kind();
  const std::int64_t silent = rig.agent_falls_silent();
  std::optional<std::int64_t> land_at, accepted_at;
  wait_for(
      [&] {
        for (const auto& c : rig.tap().commands()) {
          if (c.at_ns >= silent && fw::is_land_command(kind, c.value)) {
            land_at = c.at_ns;
            for (const auto& a : rig.tap().acks()) {
              if (a.at_ns >= c.at_ns && a.value.command == c.value.command &&
                  a.value.result == mav::mav_result::kAccepted) {
                accepted_at = a.at_ns;
                return true;
              }
            }
            return false;
          }
        }
        return false;
      },
      3s);
  const double mode_s = mode_after_s(
      rig, silent, [&](auto& hb) { return fw::in_land(kind, hb); }, 3s);
  FaultTry t;
  t.headline = land_at ? ms(silent, *land_at) : NAN;
  t.row = {{"land_command_ms", figure_json(t.headline)},
           {"land_accepted_ms", figure_json(accepted_at ? ms(silent, *accepted_at) : NAN)},
           {"land_mode_s", figure_json(mode_s)}};
  return t;
}

FaultTry link_cut(fw::FirmwareRig& rig, double height, double loss_s) {
  turn(rig, height);
  rig.tap().cut(true);
  const std::int64_t cut = now_ns();
  const auto last = rig.tap().last_setpoint();
  const std::int64_t last_ns = last ? last->at_ns : cut;
  const double firmware_s = failsafe_after_s(
      rig, last_ns, std::chrono::milliseconds(static_cast<long long>(loss_s * 1000)) + 6s);
  std::optional<std::int64_t> lost_at;
  std::string bridge_says;
  wait_for(
      [&] {
        for (const auto& s : rig.states_since(cut)) {
          if (!s.value.link_ok) {
            lost_at = s.at_ns;
            bridge_says = s.value.failsafe;
            return true;
          }
        }
        return false;
      },
      5s);
  // What the bridge asks of the firmware it no longer hears (nothing arrives).
  std::optional<std::int64_t> land_at;
  wait_for(
      [&] {
        for (const auto& c : rig.tap().commands()) {
          if (c.at_ns >= cut && fw::is_land_command(rig.firmware_kind(), c.value)) {
            land_at = c.at_ns;
            return true;
          }
        }
        return false;
      },
      3s);
  std::string bridge_sent;
  for (const auto& c : rig.tap().commands()) {
    if (c.at_ns >= cut) {
      bridge_sent += (bridge_sent.empty() ? "" : ", ") + std::to_string(c.value.command);
    }
  }
  rig.tap().cut(false);
  FaultTry t;
  t.headline = firmware_s;
  t.row = {{"firmware_failsafe_s", figure_json(firmware_s)},
           {"bridge_link_lost_s", figure_json(lost_at ? ms(cut, *lost_at) * 1e-3 : NAN)},
           {"bridge_failsafe", bridge_says},
           {"bridge_land_command_s", figure_json(land_at ? ms(cut, *land_at) * 1e-3 : NAN)},
           {"bridge_commands_during_cut", bridge_sent}};
  return t;
}

// The firmware's yaw rate every 0.1 s from 0.2 s before `at_ns` to 1 s after: how it left
// the turn, for a reader.
nlohmann::json yaw_trace(fw::FirmwareRig& rig, std::int64_t at_ns) {
  nlohmann::json trace = nlohmann::json::array();
  std::int64_t next = at_ns - 200'000'000;
  for (const auto& a : rig.monitor().attitudes_since(next)) {
    if (a.at_ns > at_ns + 1'000'000'000) break;
    if (a.at_ns < next) continue;
    trace.push_back(std::round(a.value.yawspeed * 1000.0) / 1000.0);
    next += 100'000'000;
  }
  return trace;
}

// What the firmware said (STATUSTEXT) and which modes its HEARTBEAT gave in the second
// after `at_ns`.
std::string said_after(fw::FirmwareRig& rig, std::int64_t at_ns) {
  std::string text;
  for (const auto& t : rig.monitor().texts()) {
    if (t.at_ns >= at_ns && t.at_ns < at_ns + 1'000'000'000) text += "'" + t.value + "' ";
  }
  std::uint32_t mode = 0xFFFFFFFF;
  for (const auto& hb : rig.monitor().heartbeats_since(at_ns - 1'000'000'000)) {
    if (hb.at_ns > at_ns + 1'000'000'000) break;
    if (hb.value.custom_mode != mode) {
      mode = hb.value.custom_mode;
      text += "mode " + std::to_string(mode) + " at " +
              figure_text("%.2f s", ms(at_ns, hb.at_ns) * 1e-3) + "; ";
    }
  }
  return text;
}

FaultTry bridge_killed(fw::FirmwareRig& rig, double height, double loss_s) {
  turn(rig, height);
  rig.kill_bridge();
  const auto last = rig.tap().last_setpoint();
  const std::int64_t last_ns = last ? last->at_ns : now_ns();
  const double firmware_s = failsafe_after_s(
      rig, last_ns, std::chrono::milliseconds(static_cast<long long>(loss_s * 1000)) + 6s);
  const cover::Autopilot kind = rig.firmware_kind();
  const double mode_s =
      kind == cover::Autopilot::Px4
          ? mode_after_s(
                rig, last_ns, [&](auto& hb) { return fw::in_land(kind, hb); }, 3s)
          : NAN;  // ArduCopter stays in GUIDED_NOGPS: it levels and holds its altitude
  const std::int64_t restarted = now_ns();
  rig.restart_bridge();
  require(wait_for(
              [&] {
                for (const auto& s : rig.states_since(restarted)) {
                  if (s.value.link_ok && s.value.system_id != 0) return true;
                }
                return false;
              },
              30s),
          "the restarted bridge's link");
  // The bridge asks for 1 s of the agent's setpoints before it asks for offboard, counted
  // from its own start.
  require(wait_for(
              [&] {
                std::int64_t streaming_since = 0;
                for (const auto& s : rig.states_since(restarted)) {
                  if (s.value.setpoint_rate_hz < 80.0) {
                    streaming_since = 0;
                  } else if (streaming_since == 0) {
                    streaming_since = s.at_ns;
                  }
                }
                return streaming_since != 0 && now_ns() - streaming_since > 1'200'000'000;
              },
              10s),
          "the agent's stream at the restarted bridge");
  FaultTry t;
  t.headline = firmware_s;
  t.row = {{"firmware_failsafe_s", figure_json(firmware_s)},
           {"land_mode_s", figure_json(mode_s)},
           {"yaw_rate_after", yaw_trace(rig, last_ns)},
           {"firmware_after", said_after(rig, last_ns)}};
  return t;
}

nlohmann::json summary(const std::string& fault, const std::vector<FaultTry>& tries,
                       const std::string& headline, const std::string& note) {
  std::vector<double> values;
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& t : tries) {
    rows.push_back(t.row);
    if (std::isfinite(t.headline)) values.push_back(t.headline);
  }
  return {{"fault", fault},
          {"figure", headline},
          {"median", figure_json(median(values))},
          {"worst", figure_json(worst(values))},
          {"measured", values.size()},
          {"tries", rows},
          {"note", note}};
}

// --- one autopilot ---------------------------------------------------------------------------

// A fault the benchmark injects --tries times, and the figure its table shows.
struct FaultPlan {
  std::string fault;
  std::string figure;
  std::string note;
  std::function<FaultTry(fw::FirmwareRig&, double height, double loss_s)> run;
};

std::vector<FaultPlan> fault_plans(const fw::FirmwareProfile& profile) {
  const std::string loss = " (" + profile.offboard_loss_param + ")";
  return {{"agent_killed", "land_command_ms",
           "the agent's last command -> the bridge's land command on the link",
           [](fw::FirmwareRig& rig, double, double) { return agent_killed(rig); }},
          {"heartbeat_loss", "firmware_failsafe_s",
           "link cut both ways -> the firmware's own failsafe" + loss, &link_cut},
          {"bridge_killed", "firmware_failsafe_s", "SIGKILL -> the firmware's own failsafe" + loss,
           &bridge_killed}};
}

struct Options {
  int tries = 3;
  int hold_s = 10;
  std::filesystem::path workdir;
};

nlohmann::json fly_autopilot(const fw::FirmwareProfile& profile, const fw::FirmwareBuild& build,
                             const Options& options, cover::bench::NotMeasured& missing) {
  const std::string name = profile.bridge_autopilot;
  nlohmann::json out{
      {"autopilot", name},
      {"firmware",
       profile.firmware == cover::Autopilot::Px4 ? "PX4 SITL, SIH quad" : "ArduCopter SITL, quad"}};
  fw::RigSetup setup;
  setup.fc_bridge = cover::bench::cover_binary("cover-fc-bridge");
  setup.cli = cover::bench::cover_binary("cover");
  setup.workdir = options.workdir / name;
  setup.log = stderr;
  // As the launch files run them: the agent's stream must not miss cmd_timeout_s because
  // the machine is busy.
  setup.bridge_priority = 55;
  setup.agent_priority = 50;
  fw::FirmwareRig rig(setup, profile, build, profile.flight_params, profile.bridge_hover_start);
  out["console_log"] = rig.firmware().console_log().string();
  std::string stage = "arm and take off";
  out["faults"] = nlohmann::json::array();
  std::optional<FaultPlan> current;
  std::vector<FaultTry> tries;
  const auto open_fault = [&](const FaultPlan& plan) {
    current = plan;
    stage = plan.fault;
    tries.clear();
  };
  const auto close_fault = [&] {
    if (current)
      out["faults"].push_back(summary(current->fault, tries, current->figure, current->note));
    current.reset();
  };
  try {
    const double height = arm_and_take_off(rig);
    const std::int64_t airborne = now_ns();
    const auto before = fw::firmware_hover_thrust(profile.firmware, rig.monitor());

    stage = "setpoint rate and latency";
    const RateAndLatency rl = rate_and_latency(rig, height, std::chrono::seconds(options.hold_s));
    still_flying(rig, stage);
    out["setpoint_rate_hz"] = {
        {"median", figure_json(median(rl.window_hz))},
        {"worst_window", figure_json(rl.window_hz.empty() ? NAN
                                                          : *std::min_element(rl.window_hz.begin(),
                                                                              rl.window_hz.end()))},
        {"windows", rl.window_hz.size()}};
    out["latency_ms"] = {{"to_firmware_p50", figure_json(percentile(rl.to_firmware_ms, 0.5))},
                         {"to_firmware_p99", figure_json(percentile(rl.to_firmware_ms, 0.99))},
                         {"echo_p50", figure_json(percentile(rl.echo_ms, 0.5))},
                         {"echo_p99", figure_json(percentile(rl.echo_ms, 0.99))},
                         {"echo_rate_hz", figure_json(rl.echo_rate_hz)},
                         {"steps", rl.steps},
                         {"matched_to_firmware", rl.to_firmware_ms.size()},
                         {"matched_echo", rl.echo_ms.size()},
                         {"echo_note", rl.echo_note}};
    if (rl.window_hz.empty()) missing.add(name + " setpoint rate: no 1 s window flown");
    if (rl.to_firmware_ms.empty())
      missing.add(name + " command -> firmware latency: no setpoint matched");
    if (rl.echo_ms.empty())
      missing.add(name + " command -> ATTITUDE_TARGET latency: " + rl.echo_note);

    stage = "hover estimate";
    const Hover h = hover_estimate(rig, before.value_or(NAN), airborne);
    still_flying(rig, stage);
    out["hover"] = {{"estimate", figure_json(h.estimate)},
                    {"firmware", figure_json(h.truth)},
                    {"firmware_source", h.truth_source},
                    {"error_percent", figure_json(h.error_percent)},
                    {"settled_after_s", figure_json(h.settle_s)},
                    {"started_at", profile.bridge_hover_start}};
    if (!std::isfinite(h.error_percent))
      missing.add(name + " hover-thrust error: " + h.truth_source);

    stage = "rate step";
    const Step st = rate_step(rig, height);
    still_flying(rig, stage);
    out["rate_step"] = {{"rate_rad_s", kStepRate_rad_s},
                        {"duration_ms", kStepDuration.count()},
                        {"rise_90_ms", figure_json(st.rise_90_ms)},
                        {"overshoot_percent", figure_json(st.overshoot_percent)},
                        {"steady_error_rad_s", figure_json(st.steady_error_rad_s)},
                        {"attitude_report_hz", figure_json(st.report_hz)}};
    if (!std::isfinite(st.rise_90_ms))
      missing.add(name + " rate step: the roll rate never reached 90 %");

    const auto loss = rig.monitor().read_param(profile.offboard_loss_param, 5s);
    require(loss.has_value(), profile.offboard_loss_param + " not read");
    const double loss_s = loss->value(profile.bytewise_params);
    out["offboard_loss_param"] = {{"name", profile.offboard_loss_param}, {"value_s", loss_s}};
    for (const FaultPlan& plan : fault_plans(profile)) {
      open_fault(plan);
      for (int i = 0; i < options.tries; ++i) {
        tries.push_back(plan.run(rig, height, loss_s));
        take_back(rig, height);
      }
      close_fault();
    }
    for (const auto& f : out["faults"]) {
      if (f["measured"].get<std::size_t>() < static_cast<std::size_t>(options.tries)) {
        missing.add(name + " " + f["fault"].get<std::string>() + ": " +
                    std::to_string(f["measured"].get<std::size_t>()) + " of " +
                    std::to_string(options.tries) + " tries measured");
      }
    }
  } catch (const Failed& f) {
    close_fault();  // the tries it did measure
    out["failed"] = stage + ": " + f.what;
    missing.add(name + ": the flight stopped at " + stage + " (" + f.what + "), see " +
                rig.firmware().console_log().string());
  }
  return out;
}

// --- output ----------------------------------------------------------------------------------

double num(const nlohmann::json& j, const std::string& a, const std::string& b) {
  if (!j.contains(a) || !j[a].contains(b) || !j[a][b].is_number()) return NAN;
  return j[a][b].get<double>();
}

const nlohmann::json* fault(const nlohmann::json& ap, const std::string& name) {
  if (!ap.contains("faults")) return nullptr;
  for (const auto& f : ap["faults"]) {
    if (f["fault"] == name) return &f;
  }
  return nullptr;
}

std::string fault_text(const nlohmann::json& ap, const std::string& name, const char* format) {
  const nlohmann::json* f = fault(ap, name);
  if (f == nullptr) return "not measured";
  const auto value = [&](const char* k) {
    return (*f)[k].is_number() ? (*f)[k].get<double>() : NAN;
  };
  return figure_text(format, value("median")) + " / " + figure_text(format, value("worst"));
}

void print_table(const nlohmann::json& autopilots) {
  for (const auto& ap : autopilots) {
    std::printf("%s (%s)\n", ap["autopilot"].get<std::string>().c_str(),
                ap["firmware"].get<std::string>().c_str());
    if (ap.contains("failed"))
      std::printf("  FLIGHT STOPPED: %s\n", ap["failed"].get<std::string>().c_str());
    std::printf("  setpoints at the firmware     %s median, %s worst 1 s window\n",
                figure_text("%.1f Hz", num(ap, "setpoint_rate_hz", "median")).c_str(),
                figure_text("%.0f Hz", num(ap, "setpoint_rate_hz", "worst_window")).c_str());
    std::printf("  command -> firmware socket    p50 %s  p99 %s\n",
                figure_text("%.2f ms", num(ap, "latency_ms", "to_firmware_p50")).c_str(),
                figure_text("%.2f ms", num(ap, "latency_ms", "to_firmware_p99")).c_str());
    std::printf("  command -> ATTITUDE_TARGET    p50 %s  p99 %s  (reported at %s)\n",
                figure_text("%.1f ms", num(ap, "latency_ms", "echo_p50")).c_str(),
                figure_text("%.1f ms", num(ap, "latency_ms", "echo_p99")).c_str(),
                figure_text("%.0f Hz", num(ap, "latency_ms", "echo_rate_hz")).c_str());
    std::printf("  hover-thrust estimate         %s vs the firmware's %s: error %s\n",
                figure_text("%.4f", num(ap, "hover", "estimate")).c_str(),
                figure_text("%.4f", num(ap, "hover", "firmware")).c_str(),
                figure_text("%.1f %%", num(ap, "hover", "error_percent")).c_str());
    std::printf("  roll-rate step %.1f rad/s      rise 90 %% %s, overshoot %s, steady error %s\n",
                kStepRate_rad_s, figure_text("%.0f ms", num(ap, "rate_step", "rise_90_ms")).c_str(),
                figure_text("%.0f %%", num(ap, "rate_step", "overshoot_percent")).c_str(),
                figure_text("%.3f rad/s", num(ap, "rate_step", "steady_error_rad_s")).c_str());
    std::printf("  agent killed: land command    %s (median / worst; target <= %.0f ms)\n",
                fault_text(ap, "agent_killed", "%.0f ms").c_str(), kLandTarget_ms);
    std::printf("  link cut: firmware failsafe   %s\n",
                fault_text(ap, "heartbeat_loss", "%.2f s").c_str());
    std::printf("  bridge killed: fw failsafe    %s (%s %s s)\n",
                fault_text(ap, "bridge_killed", "%.2f s").c_str(),
                ap.contains("offboard_loss_param")
                    ? ap["offboard_loss_param"]["name"].get<std::string>().c_str()
                    : "",
                ap.contains("offboard_loss_param")
                    ? figure_text("%g", ap["offboard_loss_param"]["value_s"].get<double>()).c_str()
                    : "?");
  }
}

int run(const std::vector<std::string>& args) {
  CLI::App app{
      "cover-fc-bridge against the real firmware (COVER_PX4_SITL, COVER_ARDUPILOT_SITL): "
      "setpoints per second at the firmware, command -> firmware setpoint latency (at its socket "
      "and as its ATTITUDE_TARGET reports it), hover-thrust estimate error, a roll-rate step, and "
      "faults (agent killed, link cut both ways, bridge killed), --tries each."};
  bool json = false;
  std::string autopilot = "all";
  Options options;
  app.add_flag("--json", json, "print JSON");
  app.add_option("--autopilot", autopilot, "px4 | ardupilot | all")
      ->check(CLI::IsMember({"px4", "ardupilot", "all"}))
      ->capture_default_str();
  app.add_option("--tries", options.tries, "tries of each fault")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  app.add_option("--hold-s", options.hold_s,
                 "seconds of the hold the setpoint rate and latency are measured over")
      ->check(CLI::Range(2, 600))
      ->capture_default_str();
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  cover::bench::NotMeasured missing;
  options.workdir = std::filesystem::temp_directory_path() /
                    ("cover-bench-firmware-" + std::to_string(::getpid()));
  nlohmann::json autopilots = nlohmann::json::array();
  for (const std::string name : {"px4", "ardupilot"}) {
    if (autopilot != "all" && autopilot != name) continue;
    const fw::FirmwareLookup lookup =
        name == "px4" ? fw::find_px4_sitl() : fw::find_arducopter_sitl();
    if (!lookup.build) {
      missing.add(name + ": " + lookup.missing);
      continue;
    }
    const fw::FirmwareProfile profile =
        name == "px4" ? fw::px4_sih_profile() : fw::arducopter_profile();
    autopilots.push_back(fly_autopilot(profile, *lookup.build, options, missing));
  }
  if (json) {
    nlohmann::json out{{"autopilots", autopilots},
                       {"land_target_ms", kLandTarget_ms},
                       {"not_measured", missing.reasons()}};
    std::cout << out.dump(2) << "\n";
  } else {
    print_table(autopilots);
  }
  // The firmware's files stay for a look when something was not measured.
  if (missing.empty()) std::filesystem::remove_all(options.workdir);
  return missing.exit_code("firmware");
}

const cover::bench::Registrar registrar{
    "firmware",
    "the bridge against the real PX4 / ArduCopter SITL: setpoint rate, latency, hover "
    "estimate, rate step, faults",
    &run};

}  // namespace
