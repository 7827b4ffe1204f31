#pragma once
// One firmware test's whole setup: a fresh real firmware instance (its own instance number,
// ports and scratch working directory), the LinkTap on its companion link, the real
// cover-fc-bridge process on a DDS domain of the test's own, the test's FirmwareMonitor on
// the firmware's ground-station port, a DDS participant reading cover/uav/0/fc, and the
// agent's command stream when the test starts it. `cover fc ...` runs as the operator runs
// it. Everything is stopped when the rig goes.
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "agent_stream.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/firmware/firmware_monitor.hpp"
#include "cover/firmware/link_tap.hpp"
#include "cover/firmware/sitl_process.hpp"
#include "cover/process/child_process.hpp"
#include "firmware_profile.hpp"

namespace cover::firmware::test {

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout
};

class FirmwareRig {
 public:
  // Starts the firmware with `params` and the bridge with its hover-thrust estimate at
  // `bridge_hover_thrust` (0: the bridge's configured default).
  FirmwareRig(const FirmwareProfile& profile, const FirmwareBuild& build,
              const FirmwareParams& params, double bridge_hover_thrust = 0.0);
  ~FirmwareRig();
  FirmwareRig(const FirmwareRig&) = delete;
  FirmwareRig& operator=(const FirmwareRig&) = delete;

  const FirmwareProfile& profile() const { return profile_; }
  Firmware firmware_kind() const { return profile_.firmware; }
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

 private:
  FirmwareProfile profile_;
  dds::DomainClaim domain_;
  int bridge_port_ = 0;
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

}  // namespace cover::firmware::test
