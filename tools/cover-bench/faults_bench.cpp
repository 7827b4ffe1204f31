// cover-bench faults: Scenario 2 as real processes (realtime) with one fault injected per
// run at a seeded time (docs/failsafes.md): how long until a failsafe took over, and how
// the flight ended. Ground truth from the simulator's shared-memory world.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/clock/clock.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/firmware/firmware_monitor.hpp"
#include "cover/firmware/firmware_profile.hpp"
#include "cover/firmware/sitl_ports.hpp"
#include "cover/process/child_process.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/shm/seqlock_reader.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "cover_binary.hpp"
#include "fault_row.hpp"
#include "not_measured.hpp"
#include "vendor_mix.hpp"
#include "wifi_runs.hpp"

namespace {

using namespace std::chrono_literals;
using cover::bench::FaultRow;
using cover::msg::FailsafeState;
using cover::process::ChildProcess;
using cover::sim::OffboardState;
using cover::sim::SharedWorld;
using Clock = std::chrono::steady_clock;

// The faults injected into one run each; wifi_loss runs the whole flight over
// scripts/wifi-sim's lossy network instead (wifi_runs.hpp).
// The last three fly through cover-fc-bridge and the simulator's PX4 autopilot over
// MAVLink (docs/flight-controller.md).
const std::vector<std::string> kFaults = {"uav_agent_kill",     "ugv_agent_kill",
                                          "relative_state_gap", "mocap_dropout",
                                          "imu_fault",          "sim_kill",
                                          "wifi_loss",          "bridge_kill",
                                          "fc_heartbeat_loss",  "agent_kill_with_bridge"};
bool through_bridge(const std::string& fault) {
  return fault == "bridge_kill" || fault == "fc_heartbeat_loss" ||
         fault == "agent_kill_with_bridge";
}
// The bridge's and the autopilot's UDP ports of a run on `domain` (PX4 SITL's 14540 / 14580
// moved per domain, so that runs and a developer's own launch never share one).
int bridge_port(int domain) {
  return 25000 + 2 * domain;
}
constexpr const char* kWifiFault = "wifi_loss";
// --mix alternate: seed s flies the (s - 1) % 3-th vendor mix, so every fault meets each
// mix at no extra cost.
constexpr const char* kAlternate = "alternate";
constexpr double kGapDuration_s = 0.5;
// Harder than this, or tilted beyond kSafeTilt_rad at contact, is a crash. A nominal deck
// landing disarms within action_tolerance_m (5 cm) and drops: ~1.0 m/s by design.
constexpr double kSafeTouchdown_m_s = 1.5;
constexpr double kSafeTilt_rad = 0.5;
constexpr int kTargetUgv = 1;  // Scenario 2 lands on G1

// What the probe hears: the UAV agent's failsafe changes, the newest input stamps.
class Probe {
 public:
  Probe(int domain) : participant_(options(domain)) {
    trace_ = participant_.make_reader(
        cover::dds::topics::uav_trace(0), [this](const cover::msg::ControlTrace& t) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (changes_.empty() || changes_.back().second != t.failsafe) {
            changes_.push_back({t.stamp_ns * 1e-9, t.failsafe});
          }
          reference_ugv_ = static_cast<int>(t.reference_ugv);
        });
    for (std::uint32_t k = 0; k < 2; ++k) {
      imu_.push_back(participant_.make_reader(
          cover::dds::topics::ugv_imu(k), [this, k](const cover::msg::UgvImu& m) {
            std::lock_guard<std::mutex> lock(mutex_);
            last_imu_s_[k] = std::max(last_imu_s_[k], m.stamp_ns * 1e-9);
          }));
      relative_.push_back(participant_.make_reader(
          cover::dds::topics::relative_state(0, k), [this, k](const cover::msg::RelativeState& m) {
            std::lock_guard<std::mutex> lock(mutex_);
            last_relative_s_[k] = std::max(last_relative_s_[k], m.stamp_ns * 1e-9);
          }));
    }
  }
  // The first change into one of `states` stamped at or after `after_s`; NaN: none.
  double first(const std::vector<FailsafeState>& states, double after_s) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [t, s] : changes_) {
      if (t >= after_s && std::find(states.begin(), states.end(), s) != states.end()) return t;
    }
    return NAN;
  }
  int reference_ugv() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return reference_ugv_;
  }
  double last_imu_s(int k) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_imu_s_[k];
  }
  double last_relative_s(int k) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_relative_s_[k];
  }

 private:
  static cover::dds::ParticipantOptions options(int domain) {
    cover::dds::ParticipantOptions o;
    o.vendor = cover::dds::Vendor::Cyclone;
    o.domain_id = domain;
    return o;
  }
  cover::dds::Participant participant_;
  mutable std::mutex mutex_;
  std::vector<std::pair<double, FailsafeState>> changes_;
  int reference_ugv_ = 0;
  double last_imu_s_[2] = {0.0, 0.0};
  double last_relative_s_[2] = {0.0, 0.0};
  cover::dds::Reader<cover::msg::ControlTrace> trace_;
  std::vector<cover::dds::Reader<cover::msg::UgvImu>> imu_;
  std::vector<cover::dds::Reader<cover::msg::RelativeState>> relative_;
};

// The UAV's contacts with a surface while the world is watched.
// The UAV's flight after its bridge was killed under a real firmware, for a reader: how
// high and how far it went (the firmware flew on without COVER).
struct AfterKill {
  std::int64_t kill_ns = 0;  // monotonic
  bool started = false;
  double start_x_m = 0.0, start_y_m = 0.0, start_z_m = 0.0;
  double peak_z_m = -1e9;
  double farthest_m = 0.0;
  void observe(const cover::sim::SharedUav& uav) {
    const auto& p = uav.state.position_m;
    if (!started) {
      started = true;
      start_x_m = p.x;
      start_y_m = p.y;
      start_z_m = p.z;
    }
    peak_z_m = std::max(peak_z_m, static_cast<double>(p.z));
    farthest_m = std::max(farthest_m, std::hypot(p.x - start_x_m, p.y - start_y_m));
  }
  std::string describe(const cover::sim::SharedUav& end) const {
    char buf[200];
    std::snprintf(
        buf, sizeof buf,
        "after the kill: from %.2f m up to %.2f m, %.1f m away at most; at the end "
        "%.2f m up, %.1f m away",
        start_z_m, peak_z_m, farthest_m, static_cast<double>(end.state.position_m.z),
        std::hypot(end.state.position_m.x - start_x_m, end.state.position_m.y - start_y_m));
    return buf;
  }
};

struct Landing {
  bool airborne = false;
  double last_vz_m_s = 0.0;
  double last_tilt_cos = 1.0;
  double touchdown_speed_m_s = NAN;  // the hardest contact after take-off
  double touchdown_tilt_cos = 1.0;   // the most tilted contact
  int touchdown_surface = -2;        // of the hardest contact: -1 ground, k: G_k's deck
  // The motors stopped in the air (a disarm before contact): the height and time it began.
  double motors_off_height_m = NAN;
  double motors_off_time_s = NAN;
  void observe(const cover::sim::SharedUav& uav, double time_s) {
    if (!uav.contact.resting) {
      if (airborne && uav.command.thrust_m_s2 == 0.0 && !std::isfinite(motors_off_height_m)) {
        motors_off_height_m = uav.state.position_m.z;
        motors_off_time_s = time_s;
      }
      airborne = true;
      // A UAV that meets a surface while its thrust still exceeds its weight is held on top
      // with its sink zeroed (sim/src/world.cpp) and rests only once the thrust drops: the
      // impact is the last sinking sample, not the one before resting.
      if (uav.state.velocity_m_s.z < -0.02 || last_vz_m_s >= 0.0)
        last_vz_m_s = uav.state.velocity_m_s.z;
      last_tilt_cos = (uav.state.attitude.eigen() * Eigen::Vector3d::UnitZ()).z();
    } else if (airborne) {
      const double speed = std::abs(last_vz_m_s);
      if (!std::isfinite(touchdown_speed_m_s) || speed > touchdown_speed_m_s) {
        touchdown_surface = uav.contact.surface;
      }
      touchdown_speed_m_s =
          std::isfinite(touchdown_speed_m_s) ? std::max(touchdown_speed_m_s, speed) : speed;
      touchdown_tilt_cos = std::min(touchdown_tilt_cos, last_tilt_cos);
      airborne = false;
      last_vz_m_s = 0.0;
    }
  }
  // For a reader of a crashed row: where the hardest contact was, and an airborne disarm.
  std::string describe() const {
    std::string text =
        "hardest contact on " +
        (touchdown_surface == -1 ? std::string("ground") : "G" + std::to_string(touchdown_surface));
    if (std::isfinite(motors_off_height_m)) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "; motors off in the air at %.2f m (t %.2f s)",
                    motors_off_height_m, motors_off_time_s);
      text += buf;
    }
    return text;
  }
};

std::string scenario_with_sensor_faults(const std::string& fault, const std::string& dir) {
  const std::string config = cover::config::default_config_dir();
  std::ifstream in(config + "/scenarios/scenario2.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string task_key = "../tasks/scenario2.yaml";
  text.replace(text.find(task_key), task_key.size(), config + "/tasks/scenario2.yaml");
  const std::string world_key = "world: {seed: 2}";
  const std::string injected = fault == "mocap_dropout"
                                   ? "\n  relative_sensor: {dropout_probability: 0.1}"
                                   : "\n  imu: {fault_probability: 0.02}";
  text.replace(text.find(world_key), world_key.size(), world_key + injected);
  const std::string path = dir + "/scenario2_" + fault + ".yaml";
  std::ofstream(path) << text;
  return path;
}

// --firmware: the faults that mean the same with a real firmware in the loop (the others
// inject into COVER's simulated autopilot or the simulator itself).
const std::vector<std::string> kFirmwareFaults = {"uav_agent_kill", "ugv_agent_kill",
                                                  "relative_state_gap", "bridge_kill"};

// A real firmware (PX4 / ArduCopter SITL) flying the run: its instance, ports and files.
struct FirmwareRun {
  std::string name;  // "px4" / "ardupilot"
  int instance = 1;
  bool px4() const { return name == "px4"; }
  cover::Autopilot autopilot() const {
    return px4() ? cover::Autopilot::Px4 : cover::Autopilot::ArduPilot;
  }
  int physics_port() const { return cover::firmware::physics_port(autopilot(), instance); }
  int mavlink_port() const { return cover::firmware::companion_port(instance); }
  std::string params_file() const {
    return cover::config::default_config_dir() +
           (px4() ? "/firmware/px4_hil.params" : "/firmware/arducopter_json.parm");
  }
};

class FaultRun {
 public:
  FaultRun(const std::string& fault, const std::string& mix, std::uint64_t seed, int domain,
           const std::string& dir, const std::optional<FirmwareRun>& firmware = std::nullopt)
      : claim_(cover::dds::DomainClaim::claim(domain, std::chrono::minutes(10))),
        firmware_(firmware),
        fault_(fault),
        domain_(domain),
        dir_(dir),
        probe_(domain) {
    row_.fault = fault;
    row_.mix = mix;
    row_.seed = seed;
    std::mt19937_64 random(seed);
    const bool whole_run = fault == "mocap_dropout" || fault == "imu_fault";
    // Scenario 2 flies for ~10 s: from the climb (2 s) to the final stage's approach (8 s).
    // Through the bridge it starts ~2 s later (setpoints stream 1 s before OFFBOARD, then
    // the arming): the same stretch of flight.
    const double start_s = through_bridge(fault) || firmware_ ? 4.0 : 2.0;
    if (!whole_run) {
      row_.fault_time_s = std::uniform_real_distribution<double>(start_s, start_s + 6.0)(random);
    }
    // One name per run, so that a crashed run's logs survive the runs after it.
    // (the fault's name cut to 12 characters: a run id is at most 40, and they stay distinct)
    run_id_ = "fb_" + std::to_string(getpid()) + "_" + fault.substr(0, 12) + "_" + mix + "_" +
              std::to_string(seed);
    const cover::bench::VendorMix& v = cover::bench::vendor_mix(mix);
    std::vector<std::string> sim{cover::bench::cover_binary("cover-sim"),
                                 "--scenario",
                                 whole_run ? scenario_with_sensor_faults(fault, dir) : "scenario2",
                                 "--clock",
                                 "realtime",
                                 "--seed",
                                 std::to_string(seed),
                                 "--run-id",
                                 run_id_};
    if (fault == "relative_state_gap") {
      sim.insert(sim.end(), {"--relative-gap", std::to_string(row_.fault_time_s),
                             std::to_string(kGapDuration_s)});
    }
    const std::string fc_port =
        std::to_string(firmware_ ? firmware_->mavlink_port() : bridge_port(domain));
    if (firmware_) {
      sim.insert(sim.end(), {"--firmware", firmware_->name, "--firmware-port-base",
                             std::to_string(firmware_->physics_port())});
      firmware_process_ =
          spawn({cover::bench::cover_binary("cover-firmware"), firmware_->name, "--instance",
                 std::to_string(firmware_->instance), "--workdir", dir_ + "/" + run_id_ + "_sitl",
                 "--params", firmware_->params_file()},
                v.sim, "firmware");
      // A ground station's link of its own: what the firmware does once the bridge, which
      // reports its mode otherwise, is gone.
      monitor_ = firmware_->px4()
                     ? cover::firmware::FirmwareMonitor::px4(firmware_->instance)
                     : cover::firmware::FirmwareMonitor::arducopter(firmware_->instance);
    } else if (through_bridge(fault)) {
      sim.insert(sim.end(), {"--fc", "px4", "--fc-peer-port-base", fc_port, "--fc-bind-port-base",
                             std::to_string(bridge_port(domain) + 1)});
    }
    if (fault == "fc_heartbeat_loss") {
      sim.insert(sim.end(), {"--fc-heartbeat-stop", std::to_string(row_.fault_time_s)});
    }
    sim_ = spawn(sim, v.sim, "sim");
    for (int k = 0; k < 2; ++k) {
      ugvs_.push_back(spawn({cover::bench::cover_binary("cover-ugv-agent"), "--id",
                             std::to_string(k), "--run-id", run_id_},
                            v.ugv, "ugv" + std::to_string(k)));
    }
    open_world();
    std::vector<std::string> uav{cover::bench::cover_binary("cover-uav-agent"),
                                 "--id",
                                 "0",
                                 "--clock",
                                 "realtime",
                                 "--ugv-count",
                                 "2",
                                 "--task",
                                 cover::config::default_config_dir() + "/tasks/scenario2.yaml"};
    if (through_bridge(fault) || firmware_) {
      uav.push_back("--fc-bridge");
      std::vector<std::string> bridge{cover::bench::cover_binary("cover-fc-bridge"),
                                      "--id",
                                      "0",
                                      "--autopilot",
                                      firmware_ ? firmware_->name : "px4",
                                      "--url",
                                      "udpin://127.0.0.1:" + fc_port,
                                      "--clock",
                                      "realtime",
                                      "--auto-arm"};
      if (firmware_) bridge.push_back("--real-firmware");
      bridge_ = spawn(bridge, v.uav, "bridge");
    }
    uav_ = spawn(uav, v.uav, "uav");
  }
  ~FaultRun() {
    world_.reset();
    for (auto* child : {uav_.get(), bridge_.get(), ugvs_[0].get(), ugvs_[1].get(), sim_.get(),
                        firmware_process_.get()}) {
      if (child) child->terminate(10s, SIGINT);
    }
  }

  FaultRow run() {
    if (std::isfinite(row_.fault_time_s)) {
      if (watch([&](const SharedWorld& w) { return w.time_s >= row_.fault_time_s; }, 60s)) {
        inject();
      } else {
        row_.detail = "not injected: the run ended before the fault time";
      }
    }
    finish();
    return row_;
  }

 private:
  std::unique_ptr<ChildProcess> spawn(const std::vector<std::string>& argv,
                                      const std::string& vendor, const std::string& name) {
    cover::process::SpawnOptions o;
    o.extra_env = {"COVER_DDS=" + vendor, "COVER_DDS_DOMAIN=" + std::to_string(domain_)};
    o.log_file = dir_ + "/" + run_id_ + "_" + name + ".log";
    return std::make_unique<ChildProcess>(argv, o);
  }

  // The simulator's world, once it shares it (30 s at most). Throws std::runtime_error, naming
  // the simulator's exit and log, when it exits first or the world does not appear: the run
  // would measure nothing.
  void open_world() {
    const std::string name = cover::shm::segment_name(domain_, run_id_);
    const auto deadline = Clock::now() + 30s;
    std::string error;
    while (Clock::now() < deadline) {
      try {
        world_.emplace(cover::shm::SeqlockReader<SharedWorld>::open(
            name, cover::sim::kWorldSegmentLayoutVersion, 100ms));
        return;
      } catch (const std::runtime_error& e) {
        error = e.what();
      }
      if (const auto code = sim_->wait(0ms)) {
        throw std::runtime_error("cover-sim exited with code " + std::to_string(*code) +
                                 " before sharing its world; see " + dir_ + "/" + run_id_ +
                                 "_sim.log");
      }
    }
    throw std::runtime_error("the simulator's world " + name + ": " + error);
  }

  // Polls the world (tracking the landing) until `until` holds; false on timeout or when
  // the world is gone.
  bool watch(const std::function<bool(const SharedWorld&)>& until,
             std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline && world_) {
      if (world_->read(*last_) && last_->time_s > 0.0) {
        landing_.observe(last_->uavs[0], last_->time_s);
        if (after_kill_) after_kill_->observe(last_->uavs[0]);
        if (until(*last_)) return true;
      }
      if (sim_exit_ = sim_->wait(0ms); sim_exit_) return false;
      std::this_thread::sleep_for(2ms);
    }
    return false;
  }

  void inject() {
    const int reference = probe_.reference_ugv();
    const double world_at_fault_s = last_->time_s;
    if (fault_ == "bridge_kill" && firmware_) {
      kill_bridge_under_firmware();
    } else if (fault_ == "uav_agent_kill" || fault_ == "agent_kill_with_bridge" ||
               fault_ == "bridge_kill") {
      // The flight controller takes over: the simulated one's offboard loss, or the
      // autopilot's land mode (requested by the bridge, or PX4's own offboard loss when the
      // bridge is the one killed).
      ChildProcess& victim = fault_ == "bridge_kill" ? *bridge_ : *uav_;
      kill(victim.pid(), SIGKILL);
      victim.wait(5s);
      double loss_s = NAN;
      if (watch(
              [&](const SharedWorld& w) {
                loss_s = w.time_s;
                return w.uavs[0].offboard == OffboardState::LossDescent;
              },
              5s)) {
        row_.time_to_failsafe_ms = (loss_s - world_at_fault_s) * 1e3;
      }
    } else if (fault_ == "fc_heartbeat_loss") {
      // The bridge declares the link lost after heartbeat_timeout_s (1.5 s of heartbeats
      // missing, the last up to 1 s before the fault); the agent's task fails at once.
      watch([&](const SharedWorld& w) { return w.time_s >= row_.fault_time_s + 3.0; }, 10s);
      row_.time_to_failsafe_ms =
          (probe_.first({FailsafeState::FAILSAFE_AUTOPILOT_CONTROL}, row_.fault_time_s) -
           row_.fault_time_s) *
          1e3;
    } else if (fault_ == "ugv_agent_kill") {
      kill(ugvs_[reference]->pid(), SIGKILL);
      ugvs_[reference]->wait(5s);
      std::this_thread::sleep_for(500ms);  // the ladder climbs meanwhile (at 0.1 s)
      const double lost_s = probe_.last_imu_s(reference);
      row_.time_to_failsafe_ms =
          (probe_.first({FailsafeState::FAILSAFE_IMU_HOLD, FailsafeState::FAILSAFE_EMERGENCY_HOVER},
                        lost_s) -
           lost_s) *
          1e3;
      row_.detail = "killed the agent of G" + std::to_string(reference);
    } else if (fault_ == "relative_state_gap") {
      watch([&](const SharedWorld& w) { return w.time_s >= row_.fault_time_s + 0.4; }, 5s);
      const double lost_s = std::min(probe_.last_relative_s(reference), row_.fault_time_s);
      row_.time_to_failsafe_ms =
          (probe_.first({FailsafeState::FAILSAFE_EMERGENCY_HOVER}, lost_s) - lost_s) * 1e3;
    } else if (fault_ == "sim_kill") {
      const double lost_s = probe_.last_relative_s(reference);
      world_.reset();
      kill(sim_->pid(), SIGKILL);
      sim_exit_ = sim_->wait(5s);
      std::this_thread::sleep_for(500ms);
      row_.time_to_failsafe_ms =
          (probe_.first({FailsafeState::FAILSAFE_EMERGENCY_HOVER}, lost_s) - lost_s) * 1e3;
    }
  }

  // The bridge killed with a real firmware flying: nothing reports the firmware's mode to
  // the world, so its own link times its failsafe: PX4's "Failsafe activated" (offboard
  // loss), ArduCopter's "GCS Failsafe" (its bridge's HEARTBEAT watched), or its HEARTBEAT
  // in land mode (1 Hz), whichever comes first.
  void kill_bridge_under_firmware() {
    after_kill_.emplace();
    const std::int64_t kill_ns = cover::clock::monotonic_ns();
    after_kill_->kill_ns = kill_ns;
    kill(bridge_->pid(), SIGKILL);
    bridge_->wait(5s);
    std::optional<std::int64_t> land_ns;
    watch(
        [&](const SharedWorld&) {
          land_ns = firmware_failsafe_ns(kill_ns);
          return land_ns.has_value();
        },
        20s);
    if (!land_ns) {
      row_.detail = "no failsafe of the firmware's within 20 s of the kill";
      return;
    }
    row_.time_to_failsafe_ms = static_cast<double>(*land_ns - kill_ns) * 1e-6;
  }

  // What the firmware said since the kill, and whether it is armed now.
  std::string firmware_said() const {
    std::string text;
    int n = 0;
    for (const auto& t : monitor_->texts()) {
      if (t.at_ns < after_kill_->kill_ns || ++n > 8) continue;
      text += " '" + t.value + "'";
    }
    const auto hb = monitor_->heartbeat();
    return "; the firmware said" + (text.empty() ? std::string(" nothing") : text) +
           (hb ? (cover::firmware::armed(*hb) ? ", armed" : ", disarmed") +
                     (", mode " + std::to_string(hb->custom_mode))
               : std::string(", no HEARTBEAT"));
  }

  std::optional<std::int64_t> firmware_failsafe_ns(std::int64_t since_ns) const {
    std::optional<std::int64_t> first;
    for (const auto& text : monitor_->texts()) {
      if (text.at_ns >= since_ns && text.value.find("Failsafe") != std::string::npos) {
        first = text.at_ns;
        break;
      }
    }
    for (const auto& hb : monitor_->heartbeats_since(since_ns)) {
      if (cover::firmware::in_land(firmware_->autopilot(), hb.value)) {
        if (!first || hb.at_ns < *first) first = hb.at_ns;
        break;
      }
    }
    return first;
  }

  void finish() {
    if (fault_ == "sim_kill") {
      finish_without_world();
      return;
    }
    // Nobody will end the task: the agent is gone, or it failed the task (its autopilot
    // link lost, its bridge gone) and the autopilot lands on its own.
    const bool agent_gone = fault_ == "uav_agent_kill" || through_bridge(fault_);
    // A firmware stops its motors itself (PX4 2 s after landing, ArduCopter on its delay):
    // its rotors then spin down, their thrust never exactly 0.
    const auto disarmed_now = [&](const cover::sim::SharedUav& uav) {
      if (firmware_) {
        // With the bridge gone only the firmware's own link says it disarmed.
        const auto heartbeat = monitor_ ? monitor_->heartbeat() : std::nullopt;
        return uav.offboard == OffboardState::LossDisarmed ||
               uav.offboard == OffboardState::WaitingForAgent ||
               (fault_ == "bridge_kill" && heartbeat && !cover::firmware::armed(*heartbeat));
      }
      return agent_gone ? uav.offboard == OffboardState::LossDisarmed
                        : uav.command.thrust_m_s2 == 0.0;
    };
    // Until the run is over (the simulator exits when the task has ended), or the UAV rests
    // disarmed when nobody will end the task.
    watch(
        [&](const SharedWorld& w) {
          const auto& uav = w.uavs[0];
          const bool disarmed = disarmed_now(uav);
          return uav.contact.resting && disarmed && landing_.touchdown_speed_m_s >= 0.0 &&
                 (agent_gone || row_.fault == "ugv_agent_kill");
        },
        90s);
    if (!sim_exit_) sim_exit_ = sim_->wait(agent_gone ? 0ms : 30s);
    const auto& uav = last_->uavs[0];
    row_.touchdown_speed_m_s = landing_.touchdown_speed_m_s;
    if (uav.contact.resting && uav.contact.surface == kTargetUgv) {
      row_.landing_error_m =
          std::hypot(uav.contact.offset_in_surface_m.x, uav.contact.offset_in_surface_m.y);
    }
    const bool soft = std::isfinite(landing_.touchdown_speed_m_s) &&
                      landing_.touchdown_speed_m_s <= kSafeTouchdown_m_s &&
                      landing_.touchdown_tilt_cos > std::cos(kSafeTilt_rad);
    if (sim_exit_ == 0 && soft) {
      row_.outcome = "completed";
    } else if (uav.contact.resting && soft) {
      row_.outcome = "landed_safely";
    } else {
      row_.outcome = "crashed";
    }
    if (after_kill_) {
      if (!row_.detail.empty()) row_.detail += "; ";
      row_.detail += after_kill_->describe(uav) + firmware_said();
    }
    if (!row_.detail.empty()) row_.detail += "; ";
    row_.detail +=
        "simulator exit " + (sim_exit_ ? std::to_string(*sim_exit_) : "-") + ", at rest on " +
        (uav.contact.surface < 0 ? "ground" : "G" + std::to_string(uav.contact.surface)) + "; " +
        landing_.describe();
  }

  // The plant is gone with the simulator: what can be judged is whether every agent
  // stopped commanding (the UAV agent's blind landing disarmed, the UGV agents exited).
  void finish_without_world() {
    const auto deadline = Clock::now() + 20s;
    while (Clock::now() < deadline &&
           !std::isfinite(probe_.first({FailsafeState::FAILSAFE_EMERGENCY_LANDED}, 0.0))) {
      std::this_thread::sleep_for(50ms);
    }
    const bool agent_disarmed =
        std::isfinite(probe_.first({FailsafeState::FAILSAFE_EMERGENCY_LANDED}, 0.0));
    int ugvs_exited = 0;
    for (auto& ugv : ugvs_) ugvs_exited += ugv->wait(5s).has_value() ? 1 : 0;
    row_.outcome = agent_disarmed && ugvs_exited == 2 ? "landed_safely" : "crashed";
    row_.detail = std::string("world gone; UAV agent ") +
                  (agent_disarmed ? "disarmed after its blind landing" : "still armed") + ", " +
                  std::to_string(ugvs_exited) + "/2 UGV agents exited";
  }

  // First: the domain is this run's until every process of it has stopped (a test or
  // another benchmark publishing there once ended a run with its own UAV 0's samples).
  cover::dds::DomainClaim claim_;
  std::optional<FirmwareRun> firmware_;  // --firmware: the real firmware flies the UAV
  std::string fault_;
  int domain_;
  std::string dir_;
  std::string run_id_;
  FaultRow row_;
  Probe probe_;
  std::unique_ptr<ChildProcess> sim_;
  std::vector<std::unique_ptr<ChildProcess>> ugvs_;
  std::unique_ptr<ChildProcess> uav_;
  std::unique_ptr<ChildProcess> bridge_;            // the flight-controller faults, or --firmware
  std::unique_ptr<ChildProcess> firmware_process_;  // --firmware: cover-firmware
  std::unique_ptr<cover::firmware::FirmwareMonitor> monitor_;  // --firmware: its GCS link
  std::optional<AfterKill> after_kill_;  // bridge_kill under a firmware: where the UAV went
  std::optional<cover::shm::SeqlockReader<SharedWorld>> world_;
  std::unique_ptr<SharedWorld> last_ = std::make_unique<SharedWorld>();
  std::optional<int> sim_exit_;
  Landing landing_;
};

void print_table(const std::vector<FaultRow>& rows) {
  std::printf("%-20s %-8s %5s %9s %9s %9s %6s %6s %6s %10s\n", "fault", "mix", "runs", "ttf p50",
              "ttf max", "td max", "done", "landed", "crash", "land err");
  std::map<std::string, std::vector<const FaultRow*>> by_fault;
  for (const FaultRow& r : rows) by_fault[r.fault + "/" + r.mix].push_back(&r);
  for (const auto& [key, group] : by_fault) {
    std::vector<double> ttf, td, err;
    int done = 0, landed = 0, crashed = 0;
    for (const FaultRow* r : group) {
      if (std::isfinite(r->time_to_failsafe_ms)) ttf.push_back(r->time_to_failsafe_ms);
      if (std::isfinite(r->touchdown_speed_m_s)) td.push_back(r->touchdown_speed_m_s);
      if (std::isfinite(r->landing_error_m)) err.push_back(r->landing_error_m);
      done += r->outcome == "completed";
      landed += r->outcome == "landed_safely";
      crashed += r->outcome == "crashed";
    }
    auto max_of = [](const std::vector<double>& v) {
      return v.empty() ? NAN : cover::bench::percentile(v, 1.0);
    };
    auto median_of = [](const std::vector<double>& v) {
      return v.empty() ? NAN : cover::bench::percentile(v, 0.5);
    };
    // "-": no run of the group had one (no failsafe entered, no touchdown, not on the deck).
    const auto cell = [](const char* format, double value) {
      return std::isfinite(value) ? cover::bench::figure_text(format, value) : std::string("-");
    };
    std::printf("%-20s %-8s %5zu %9s %9s %9s %6d %6d %6d %10s\n", group.front()->fault.c_str(),
                group.front()->mix.c_str(), group.size(), cell("%.0fms", median_of(ttf)).c_str(),
                cell("%.0fms", max_of(ttf)).c_str(), cell("%.2fm/s", max_of(td)).c_str(), done,
                landed, crashed, cell("%.3fm", max_of(err)).c_str());
  }
  std::printf(
      "ttf: input lost -> failsafe entered (the flight controller's land / offboard loss for the "
      "kills, the agent's autopilot-control for fc_heartbeat_loss); "
      "td: touchdown vertical speed\n");
}

// The mix of one seed's run: the one asked for, or the seeds in turn over every mix.
std::string mix_of_seed(const std::string& mix, std::uint64_t seed) {
  if (mix != kAlternate) return mix;
  const auto& mixes = cover::bench::vendor_mixes();
  return mixes[static_cast<std::size_t>((seed - 1) % mixes.size())].name;
}

void print_progress(const FaultRow& row) {
  std::fprintf(stderr, "%s %s seed %llu: %s\n", row.fault.c_str(), row.mix.c_str(),
               static_cast<unsigned long long>(row.seed), row.outcome.c_str());
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"Faults injected into Scenario 2 as processes (realtime): failsafe time, outcome"};
  bool json = false;
  int count = 20;
  int domain = 190;
  std::uint64_t first_seed = 1;
  std::string mix = kAlternate;
  std::vector<std::string> faults = kFaults;
  cover::bench::WifiOptions wifi;
  std::vector<std::string> mixes = cover::bench::vendor_mix_names();
  mixes.push_back(kAlternate);
  app.add_flag("--json", json, "print JSON instead of a table");
  app.add_option("--count", count, "seeded fault times per fault")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--seed", first_seed, "first seed")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--fault", faults, "only these faults")->check(CLI::IsMember(kFaults));
  app.add_option("--mix", mix,
                 "DDS vendors: fastdds | cyclone | mixed (UAV agent on Fast DDS, the rest on "
                 "Cyclone) | alternate (seeds in turn over the three); wifi_loss flies every mix "
                 "unless one is named")
      ->check(CLI::IsMember(mixes))
      ->capture_default_str();
  app.add_option("--domain", domain, "first DDS domain (one per run, 30 in turn)")
      ->check(CLI::Range(0, 202))
      ->capture_default_str();
  app.add_option("--wifi-seeds", wifi.seeds, "wifi_loss: seeds per vendor mix")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--wifi-domain", wifi.first_domain, "wifi_loss: first DDS domain (10 in turn)")
      ->check(CLI::Range(0, 222))
      ->capture_default_str();
  std::string firmware;
  app.add_option("--firmware", firmware,
                 "px4 | ardupilot: the real firmware (SITL, COVER_PX4_SITL / COVER_ARDUPILOT_SITL) "
                 "flies the UAV on cover-sim's physics, through cover-fc-bridge; faults "
                 "uav_agent_kill, ugv_agent_kill, relative_state_gap, bridge_kill")
      ->check(CLI::IsMember({"px4", "ardupilot"}));
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;
  if (!firmware.empty()) {
    if (app.count("--fault") == 0) faults = kFirmwareFaults;
    for (const std::string& fault : faults) {
      if (std::find(kFirmwareFaults.begin(), kFirmwareFaults.end(), fault) ==
          kFirmwareFaults.end()) {
        std::cerr << "cover-bench faults: --firmware: " << fault
                  << " injects into COVER's simulated autopilot or simulator; with a real "
                     "firmware: uav_agent_kill, ugv_agent_kill, relative_state_gap, bridge_kill\n";
        return 2;
      }
    }
  }
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cover_faults_" + std::to_string(getpid())))
          .string();
  std::filesystem::create_directories(dir);
  std::vector<FaultRow> rows;
  int index = 0;
  bool wifi_failed = false;
  for (const std::string& fault : faults) {
    if (fault == kWifiFault) {
      std::vector<cover::bench::VendorMix> wifi_mixes = cover::bench::vendor_mixes();
      if (mix != kAlternate) wifi_mixes = {cover::bench::vendor_mix(mix)};
      const auto result = cover::bench::run_wifi(wifi, wifi_mixes, [&](const auto& run) {
        if (!json) print_progress(run.row);
      });
      if (!result.network_up) {
        std::cerr << "cover-bench faults: wifi_loss: scripts/wifi-sim up failed (root "
                     "needed):\n"
                  << result.network_output;
        wifi_failed = true;
      }
      for (const auto& run : result.runs) rows.push_back(run.row);
      continue;
    }
    for (int i = 0; i < count; ++i, ++index) {
      const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
      std::optional<FirmwareRun> sitl;
      if (!firmware.empty()) sitl = FirmwareRun{firmware, 1 + index % 5};
      FaultRun one(fault, mix_of_seed(mix, seed), seed, domain + index % 30, dir, sitl);
      rows.push_back(one.run());
      if (!json) print_progress(rows.back());
    }
  }
  const bool all_safe = std::none_of(rows.begin(), rows.end(),
                                     [](const FaultRow& r) { return r.outcome == "crashed"; });
  if (all_safe) std::filesystem::remove_all(dir);
  if (json) {
    std::cout << cover::bench::rows_json(rows).dump(2) << "\n";
  } else {
    print_table(rows);
    if (!all_safe) std::printf("logs of the crashed runs: %s\n", dir.c_str());
  }
  return all_safe && !wifi_failed ? 0 : 1;
}

const cover::bench::Registrar kRegistrar{
    "faults", "faults injected into Scenario 2 as processes: time to failsafe, outcome", &run};

}  // namespace
