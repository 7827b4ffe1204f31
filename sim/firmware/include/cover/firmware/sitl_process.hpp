#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/instance_slot.hpp"
#include "cover/process/child_process.hpp"

namespace cover::firmware {

// Parameters given to the firmware at start: name and value as the firmware writes them.
using FirmwareParams = std::vector<std::pair<std::string, std::string>>;

// One real firmware instance (SITL) on its own instance number, working directory and
// ports, started as its own start scripts do, stopped with SIGTERM and, after a deadline,
// SIGKILL to its whole process group. Everything it writes goes into its working directory
// (its console in console.log), except what PX4 fixes in /tmp (its lock file and its
// daemon's socket, /tmp/px4_lock-N and /tmp/px4-sock-N), which stop() removes.
class SitlProcess {
 public:
  // PX4 with its built-in SIH physics (airframe 10040 sihsim_quadx), headless:
  //   PX4_SYS_AUTOSTART=10040 PX4_SIMULATOR=sihsim bin/px4 -d -i N -w WORKDIR etc
  // with each parameter as PX4_PARAM_<NAME>=<value> (PX4's rcS sets them after the airframe).
  // Its onboard link sends to UDP 14540 + N, its ground-station link binds 18570 + N.
  static SitlProcess start_px4(const FirmwareBuild& build, InstanceSlot slot,
                               const std::filesystem::path& workdir, const FirmwareParams& params);
  // PX4 for an external simulator (simulator_mavlink, airframe 10016 none_iris), headless:
  //   PX4_SYS_AUTOSTART=10016 bin/px4 -d -i N -w WORKDIR etc
  // with `params` as for start_px4 (config/firmware/px4_hil.params: read_params_file). PX4
  // connects to TCP 127.0.0.1:4560 + N (firmware_link::Px4HilLink) and its start script blocks
  // until the first HIL_SENSOR; blocked there it ignores SIGTERM (stop() then kills it).
  // MAVLink ports as start_px4's.
  static SitlProcess start_px4_hil(const FirmwareBuild& build, InstanceSlot slot,
                                   const std::filesystem::path& workdir,
                                   const FirmwareParams& params);
  // ArduCopter with SITL's built-in multicopter physics, in WORKDIR:
  //   arducopter --model quad --speedup 1 -I N --sysid N+1 -w --home 47.3977,8.5456,488,0
  //     --defaults copter.parm,WORKDIR/cover.parm --serial0 tcp:0
  //     --serial1 udpclient:127.0.0.1:<14540 + N>
  // cover.parm holds `params` (they override SITL's defaults; -w wipes what an earlier run
  // stored; written by write_arducopter_params, kOwnSystemId as N + 1). SERIAL0 is a TCP
  // server on 5760 + 10 N.
  static SitlProcess start_arducopter(const FirmwareBuild& build, InstanceSlot slot,
                                      const std::filesystem::path& workdir,
                                      const FirmwareParams& params);

  // ArduCopter flown by an external physics engine over SITL's JSON backend, in WORKDIR:
  //   arducopter --model JSON:127.0.0.1 ... (the rest as start_arducopter)
  // Each frame it sends its servo packet to UDP 127.0.0.1:<9002 + 10 N> and blocks until the
  // engine there (firmware_link's ArduPilotJsonLink) answers; bind that port first.
  static SitlProcess start_arducopter_json(const FirmwareBuild& build, InstanceSlot slot,
                                           const std::filesystem::path& workdir,
                                           const FirmwareParams& params);

  SitlProcess(SitlProcess&&) noexcept = default;
  SitlProcess& operator=(SitlProcess&&) = delete;
  ~SitlProcess();

  Autopilot firmware() const { return firmware_; }
  int instance() const { return slot_.instance(); }
  int system_id() const { return slot_.instance() + 1; }
  pid_t pid() const { return child_ ? child_->pid() : -1; }
  const std::filesystem::path& console_log() const { return console_log_; }
  // Still running (neither exited nor stopped).
  bool running();
  // SIGTERM to its process group, SIGKILL after `grace`; its exit code (128 + signal when
  // a signal ended it). Stopping twice returns the first result.
  int stop(std::chrono::milliseconds grace = std::chrono::seconds(5));

 private:
  SitlProcess(Autopilot firmware, InstanceSlot slot, std::filesystem::path console_log,
              std::unique_ptr<process::ChildProcess> child);
  void remove_px4_tmp_files() const;
  static SitlProcess start_arducopter_model(const FirmwareBuild& build, InstanceSlot slot,
                                            const std::filesystem::path& workdir,
                                            const FirmwareParams& params, const std::string& model);

  Autopilot firmware_;
  InstanceSlot slot_;
  std::filesystem::path console_log_;
  std::unique_ptr<process::ChildProcess> child_;
  std::optional<int> exit_code_;
};

}  // namespace cover::firmware
