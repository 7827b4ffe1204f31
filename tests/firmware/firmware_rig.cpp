#include "firmware_rig.hpp"

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <random>
#include <stdexcept>

#include "cover/clock/clock.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "cover/test/wait_until.hpp"

namespace cover::firmware::test {
namespace {

namespace mav = cover::mavlink;
using namespace std::chrono_literals;

// The test's DDS domains: 145..149 are no other test's (tests/fc_bridge uses 200..209).
constexpr int kFirstDomain = 145;
constexpr int kLastDomain = 149;

// A loopback UDP port free now, below Linux's ephemeral range, for the bridge's udpin.
int free_udp_port() {
  static std::mt19937 rng(static_cast<unsigned>(::getpid()) ^
                          static_cast<unsigned>(clock::monotonic_ns()));
  std::uniform_int_distribution<int> pick(20000, 32000);
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int port = pick(rng);
    if (port_free({false, port})) return port;
  }
  throw std::runtime_error("no free UDP port in 20000-32000");
}

dds::ParticipantOptions on_domain(int domain) {
  dds::ParticipantOptions options;
  options.vendor = dds::Vendor::Cyclone;
  options.domain_id = domain;
  options.participant_name = "firmware-test";
  return options;
}

}  // namespace

FirmwareRig::FirmwareRig(const FirmwareProfile& profile, const FirmwareBuild& build,
                         const FirmwareParams& params, double bridge_hover_thrust)
    : profile_(profile), domain_(dds::DomainClaim::claim_any(kFirstDomain, kLastDomain)) {
  InstanceSlot slot =
      InstanceSlot::claim(profile.firmware, profile.first_instance, profile.last_instance);
  const int n = slot.instance();
  bridge_port_ = free_udp_port();
  // The tap first: the firmware's first frames on its companion link go to it.
  tap_ = std::make_unique<LinkTap>(companion_port(n), bridge_port_);

  std::vector<std::string> argv{COVER_FC_BRIDGE,
                                "--id",
                                "0",
                                "--autopilot",
                                profile.bridge_autopilot,
                                "--url",
                                "udpin://127.0.0.1:" + std::to_string(bridge_port_),
                                "--clock",
                                "system",
                                "--dds",
                                "cyclone",
                                "--domain",
                                std::to_string(domain_.domain())};
  if (bridge_hover_thrust > 0.0) {
    argv.insert(argv.end(), {"--hover-thrust", std::to_string(bridge_hover_thrust)});
  }
  process::SpawnOptions bridge_options;
  bridge_options.log_file = cover::test::scratch_path("fc_bridge.log");
  bridge_options.null_stdin = true;
  bridge_options.close_other_fds = true;
  bridge_ = std::make_unique<process::ChildProcess>(argv, bridge_options);

  const auto workdir = cover::test::scratch_dir() / to_string(profile.firmware);
  firmware_.emplace(profile.firmware == Firmware::Px4
                        ? SitlProcess::start_px4(build, std::move(slot), workdir, params)
                        : SitlProcess::start_arducopter(build, std::move(slot), workdir, params));
  std::printf("%s SITL instance %d (system %d) in %s, bridge on UDP %d, DDS domain %d\n",
              to_string(profile.firmware), n, firmware_->system_id(), workdir.c_str(), bridge_port_,
              domain_.domain());

  monitor_ =
      profile.firmware == Firmware::Px4 ? FirmwareMonitor::px4(n) : FirmwareMonitor::arducopter(n);
  participant_ = std::make_unique<dds::Participant>(on_domain(domain_.domain()));
  fc_ = participant_->make_reader(dds::topics::fc_state(0), [this](const msg::FcState& s) {
    std::lock_guard<std::mutex> lock(states_mutex_);
    states_.push_back({clock::monotonic_ns(), s});
  });
}

FirmwareRig::~FirmwareRig() {
  agent_.reset();
  fc_ = {};  // its callback writes states_
  participant_.reset();
  if (bridge_) bridge_->terminate();
  monitor_.reset();
  if (firmware_) firmware_->stop();
  tap_.reset();
}

std::optional<msg::FcState> FirmwareRig::state() const {
  std::lock_guard<std::mutex> lock(states_mutex_);
  if (states_.empty()) return std::nullopt;
  return states_.back().value;
}

std::vector<Timed<msg::FcState>> FirmwareRig::states_since(std::int64_t since_ns) const {
  std::lock_guard<std::mutex> lock(states_mutex_);
  std::vector<Timed<msg::FcState>> out;
  for (const auto& s : states_) {
    if (s.at_ns >= since_ns) out.push_back(s);
  }
  return out;
}

CliRun FirmwareRig::cover_fc(const std::vector<std::string>& args) {
  std::vector<std::string> argv{COVER_CLI, "fc"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--dds", "cyclone", "--domain", std::to_string(domain_.domain())});
  process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = cover::test::scratch_path("cover_fc.log");
  options.append_log = true;
  options.null_stdin = true;
  process::ChildProcess cli(argv, options);
  CliRun run;
  while (const auto line = cli.read_line(cover::test::scaled(60s))) run.output += *line + "\n";
  run.exit_code = cli.wait(cover::test::scaled(20s)).value_or(-1);
  std::string shown;
  for (const auto& a : args) shown += " " + a;
  std::printf("cover fc%s -> exit %d: %s", shown.c_str(), run.exit_code,
              run.output.empty() ? "\n" : run.output.c_str());
  return run;
}

bool FirmwareRig::connect_monitor(std::chrono::milliseconds timeout) {
  if (!cover::test::wait_until([&] { return monitor_->connected(); }, timeout)) return false;
  // What the monitor reads, at rates enough to time a mode change or a failsafe to 20 ms
  // (PX4's ground-station link sends some of them already; ArduCopter nothing).
  struct Ask {
    std::uint32_t id;
    double hz;
    bool needed;
  };
  const Ask asks[] = {
      {mav::Heartbeat::kId, 50.0, false},         {mav::LocalPositionNed::kId, 50.0, true},
      {mav::AttitudeQuaternion::kId, 50.0, true}, {mav::HighresImu::kId, 50.0, false},
      {mav::ExtendedSysState::kId, 5.0, true},    {mav::SysStatus::kId, 2.0, true}};
  bool all_needed = true;
  for (const Ask& ask : asks) {
    const auto result = monitor_->request_stream(ask.id, ask.hz);
    if (!result || *result != mav::mav_result::kAccepted) {
      std::printf("monitor: the firmware %s message %u at %.0f Hz (result %d)\n",
                  result ? "refused" : "did not answer a request for", ask.id, ask.hz,
                  result ? *result : -1);
      all_needed = all_needed && !ask.needed;
    }
  }
  return all_needed;
}

bool FirmwareRig::ready_to_arm() const {
  const auto position = monitor_->position();
  const auto heartbeat = monitor_->heartbeat();
  if (!position || !heartbeat || clock::monotonic_ns() - position->at_ns > 1'000'000'000) {
    return false;
  }
  // SYS_STATUS's pre-arm bit where the firmware reports it, else PX4's "standby" state,
  // which it reaches once its pre-flight checks pass.
  const auto status = monitor_->sys_status();
  constexpr std::uint32_t kPrearm = mav::mav_sys_status_sensor::kPrearmCheck;
  if (status && (status->onboard_control_sensors_present & kPrearm) != 0) {
    return (status->onboard_control_sensors_health & kPrearm) != 0;
  }
  return heartbeat->system_status == mav::mav_state::kStandby;
}

void FirmwareRig::agent_flies(AgentStream::Policy policy) {
  if (agent_) {
    agent_->fly(std::move(policy));
  } else {
    agent_ = std::make_unique<AgentStream>(*participant_, std::move(policy));
  }
}

std::int64_t FirmwareRig::agent_falls_silent() {
  if (!agent_) return 0;
  const std::int64_t last_ns = agent_->fall_silent();
  agent_.reset();  // a later agent_flies starts a new agent, as a restarted one
  return last_ns;
}

void FirmwareRig::kill_bridge() {
  ::kill(bridge_->pid(), SIGKILL);
  bridge_->wait(cover::test::scaled(5s));
}

}  // namespace cover::firmware::test
