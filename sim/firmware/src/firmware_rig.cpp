#include "cover/firmware/firmware_rig.hpp"

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <stdexcept>
#include <thread>

#include "cover/clock/clock.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/state_messages.hpp"

namespace cover::firmware {
namespace {

using namespace std::chrono_literals;

// Polls `condition` until it holds or `timeout` passes (then one last look).
bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= end) return condition();
    std::this_thread::sleep_for(5ms);  // polling a condition with a deadline
  }
  return true;
}

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
  options.participant_name = "firmware-rig";
  return options;
}

}  // namespace

FirmwareRig::FirmwareRig(const RigSetup& setup, const FirmwareProfile& profile,
                         const FirmwareBuild& build, const FirmwareParams& params,
                         double bridge_hover_thrust)
    : setup_(setup),
      profile_(profile),
      domain_(dds::DomainClaim::claim_any(setup.first_domain, setup.last_domain)) {
  InstanceSlot slot =
      InstanceSlot::claim(profile.firmware, profile.first_instance, profile.last_instance);
  const int n = slot.instance();
  bridge_port_ = free_udp_port();
  // The tap first: the firmware's first frames on its companion link go to it.
  tap_ = std::make_unique<LinkTap>(companion_port(n), bridge_port_);

  std::filesystem::create_directories(setup_.workdir);
  std::vector<std::string> argv{setup_.fc_bridge.string(),
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
  if (!profile.bridge_params.empty()) {
    const auto params_file = setup_.workdir / "fc_bridge.yaml";
    std::ofstream yaml(params_file);
    yaml << "fc_bridge:\n";
    for (const auto& [name, value] : profile.bridge_params)
      yaml << "  " << name << ": " << value << "\n";
    argv.insert(argv.end(), {"--params", params_file.string()});
  }
  bridge_argv_ = argv;
  restart_bridge();

  const auto workdir = setup_.workdir / display_name(profile.firmware);
  firmware_.emplace(profile.firmware == Autopilot::Px4
                        ? SitlProcess::start_px4(build, std::move(slot), workdir, params)
                        : SitlProcess::start_arducopter(build, std::move(slot), workdir, params));
  std::fprintf(setup_.log,
               "%s SITL instance %d (system %d) in %s, bridge on UDP %d, DDS domain %d\n",
               display_name(profile.firmware), n, firmware_->system_id(), workdir.c_str(),
               bridge_port_, domain_.domain());

  monitor_ =
      profile.firmware == Autopilot::Px4 ? FirmwareMonitor::px4(n) : FirmwareMonitor::arducopter(n);
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
  std::vector<std::string> argv{setup_.cli.string(), "fc"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--dds", "cyclone", "--domain", std::to_string(domain_.domain())});
  process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = (setup_.workdir / "cover_fc.log").string();
  options.append_log = true;
  options.null_stdin = true;
  process::ChildProcess cli(argv, options);
  CliRun run;
  while (const auto line = cli.read_line(deadline(60s))) run.output += *line + "\n";
  run.exit_code = cli.wait(deadline(20s)).value_or(-1);
  std::string shown;
  for (const auto& a : args) shown += " " + a;
  std::fprintf(setup_.log, "cover fc%s -> exit %d: %s", shown.c_str(), run.exit_code,
               run.output.empty() ? "\n" : run.output.c_str());
  return run;
}

bool FirmwareRig::connect_monitor(std::chrono::milliseconds timeout) {
  if (!wait_until([&] { return monitor_->connected(); }, deadline(timeout))) return false;
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
      std::fprintf(setup_.log, "monitor: the firmware %s message %u at %.0f Hz (result %d)\n",
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
    agent_ = std::make_unique<AgentStream>(*participant_, std::move(policy), setup_.agent_priority);
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
  bridge_->wait(deadline(5s));
}

void FirmwareRig::restart_bridge() {
  process::SpawnOptions options;
  options.log_file = (setup_.workdir / "fc_bridge.log").string();
  options.append_log = true;
  options.null_stdin = true;
  options.close_other_fds = true;
  options.realtime_priority = setup_.bridge_priority;
  bridge_ = std::make_unique<process::ChildProcess>(bridge_argv_, options);
}

std::chrono::milliseconds FirmwareRig::deadline(std::chrono::milliseconds d) const {
  return std::chrono::milliseconds(
      static_cast<long long>(static_cast<double>(d.count()) * setup_.deadline_scale));
}

}  // namespace cover::firmware
