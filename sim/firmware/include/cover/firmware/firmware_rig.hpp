#pragma once
// One firmware run's whole setup (a firmware test's, or cover-bench firmware's): a fresh
// real firmware instance (its own instance number, ports and working directory), the
// LinkTap on its companion link, the real cover-fc-bridge process on a DDS domain of the
// run's own, a FirmwareMonitor on the firmware's ground-station port, a DDS participant
// reading cover/uav/0/fc, and the agent's command stream when the run starts it.
// `cover fc ...` runs as the operator runs it. Everything is stopped when the rig goes.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/firmware/agent_stream.hpp"
#include "cover/firmware/firmware_monitor.hpp"
#include "cover/firmware/firmware_profile.hpp"
#include "cover/firmware/link_tap.hpp"
#include "cover/firmware/sitl_process.hpp"
#include "cover/process/child_process.hpp"

namespace cover::firmware {

// Where the rig finds COVER's programs and puts its files, and how it waits.
struct RigSetup {
  std::filesystem::path fc_bridge;  // the cover-fc-bridge executable
  std::filesystem::path cli;        // the `cover` executable
  // The firmware's working directory goes in a folder of it, named after the firmware;
  // the bridge's log and the CLI's are fc_bridge.log and cover_fc.log in it.
  std::filesystem::path workdir;
  // The DDS domains the rig may claim one of (tests/fc_bridge uses 200..209).
  int first_domain = 145;
  int last_domain = 149;
  // Deadlines the rig waits on (a CLI's answer, a process's exit) are multiplied by it: a
  // test's COVER_TEST_TIME_SCALE. They are how long to wait, never a measurement.
  double deadline_scale = 1.0;
  std::FILE* log = stdout;  // what the rig says it did (a benchmark's JSON owns stdout)
  // SCHED_FIFO priorities of the bridge process and the agent's thread, as the launch files
  // give cover-fc-bridge (55) and cover-uav-agent (50); 0: the caller's policy. On a loaded
  // machine an agent at the default policy can miss the bridge's 100 ms cmd_timeout_s.
  int bridge_priority = 0;
  int agent_priority = 0;
};

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout
};

class FirmwareRig {
 public:
  // Starts the firmware with `params` and the bridge with its hover-thrust estimate at
  // `bridge_hover_thrust` (0: the bridge's configured default).
  FirmwareRig(const RigSetup& setup, const FirmwareProfile& profile, const FirmwareBuild& build,
              const FirmwareParams& params, double bridge_hover_thrust = 0.0);
  ~FirmwareRig();
  FirmwareRig(const FirmwareRig&) = delete;
  FirmwareRig& operator=(const FirmwareRig&) = delete;

  const FirmwareProfile& profile() const { return profile_; }
  Autopilot firmware_kind() const { return profile_.firmware; }
  SitlProcess& firmware() { return *firmware_; }
  FirmwareMonitor& monitor() { return *monitor_; }
  LinkTap& tap() { return *tap_; }
  process::ChildProcess& bridge() { return *bridge_; }
  int domain() const { return domain_.domain(); }

  // The bridge's newest cover/uav/0/fc, and every one since `since_ns` (monotonic).
  std::optional<msg::FcState> state() const;
  std::vector<Timed<msg::FcState>> states_since(std::int64_t since_ns) const;

  // `cover fc ARGS... --dds cyclone --domain D`, as an operator runs it.
  CliRun cover_fc(const std::vector<std::string>& args);

  // The monitor hears the firmware and has asked it for the streams it reads.
  bool connect_monitor(std::chrono::milliseconds timeout);
  // The firmware says it would arm (its pre-arm checks pass) and gives a position.
  bool ready_to_arm() const;

  // The agent starts streaming `policy` (or flies it, if it already streams).
  void agent_flies(AgentStream::Policy policy);
  // The agent falls silent: the monotonic time of its last command.
  std::int64_t agent_falls_silent();
  std::uint32_t agent_written() const { return agent_ ? agent_->written() : 0; }

  // The bridge dies as a process killed hard does (SIGKILL): no goodbye, no land.
  void kill_bridge();
  // A new cover-fc-bridge process with the first one's arguments (as a supervisor restarts
  // it), after kill_bridge.
  void restart_bridge();

  std::chrono::milliseconds deadline(std::chrono::milliseconds d) const;

 private:
  RigSetup setup_;
  FirmwareProfile profile_;
  dds::DomainClaim domain_;
  int bridge_port_ = 0;
  std::vector<std::string> bridge_argv_;
  std::unique_ptr<LinkTap> tap_;
  std::unique_ptr<process::ChildProcess> bridge_;
  std::optional<SitlProcess> firmware_;
  std::unique_ptr<FirmwareMonitor> monitor_;
  std::unique_ptr<dds::Participant> participant_;
  mutable std::mutex states_mutex_;
  std::vector<Timed<msg::FcState>> states_;
  dds::Reader<msg::FcState> fc_;
  std::unique_ptr<AgentStream> agent_;
};

}  // namespace cover::firmware
