#include "cover/firmware/sitl_process.hpp"

#include <signal.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "cover/firmware/params_file.hpp"

namespace cover::firmware {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPx4SihQuadAirframe = "10040";  // sihsim_quadx
constexpr const char* kPx4HilQuadAirframe = "10016";  // none_iris: simulator_mavlink
// ArduPilot's SITL home (its run-quad default, CMAC-like); SITL's GPS is centred on it.
constexpr const char* kArduCopterHome = "47.3977,8.5456,488,0";

process::SpawnOptions spawn_options(const fs::path& console_log) {
  process::SpawnOptions options;
  options.log_file = console_log.string();
  options.null_stdin = true;
  // Its own group: stop() reaches the firmware's own children (PX4's start-up shell and
  // the px4-* clients it runs) as well.
  options.new_process_group = true;
  options.close_other_fds = true;
  return options;
}

// PX4's start script runs its commands as px4-<module> links to the px4 binary, found on
// a PATH that starts with the directory px4 was started from (main.cpp). A build's own
// links are symbolic; a copy of a build may have them as plain files (a copy that does not
// keep links), which cannot run. So px4 starts from WORKDIR/bin, where every entry of the
// build's bin/ is a link of the test's own: px4 to the binary, px4-<module> to px4, the
// rest (px4-alias.sh) to the file. Returns the px4 to start.
fs::path link_px4_commands(const FirmwareBuild& build, const fs::path& workdir) {
  const fs::path bin = workdir / "bin";
  fs::create_directories(bin);
  const fs::path real_px4 = fs::canonical(build.binary);
  for (const auto& entry : fs::directory_iterator(build.binary.parent_path())) {
    const std::string name = entry.path().filename().string();
    const bool command = name.rfind("px4-", 0) == 0 && entry.path().extension() != ".sh";
    const fs::path target = name == "px4" ? real_px4 : command ? fs::path("px4") : entry.path();
    fs::create_symlink(target, bin / name);
  }
  return bin / "px4";
}

}  // namespace

SitlProcess::SitlProcess(Autopilot firmware, InstanceSlot slot, fs::path console_log,
                         std::unique_ptr<process::ChildProcess> child)
    : firmware_(firmware),
      slot_(std::move(slot)),
      console_log_(std::move(console_log)),
      child_(std::move(child)) {}

SitlProcess SitlProcess::start_px4(const FirmwareBuild& build, InstanceSlot slot,
                                   const fs::path& workdir, const FirmwareParams& params) {
  fs::create_directories(workdir);
  const fs::path console = workdir / "console.log";
  process::SpawnOptions options = spawn_options(console);
  options.extra_env = {std::string("PX4_SYS_AUTOSTART=") + kPx4SihQuadAirframe,
                       "PX4_SIMULATOR=sihsim"};
  for (const auto& [name, value] : params)
    options.extra_env.push_back("PX4_PARAM_" + name + "=" + value);
  const std::string n = std::to_string(slot.instance());
  const fs::path px4 = link_px4_commands(build, workdir);
  auto child = std::make_unique<process::ChildProcess>(
      std::vector<std::string>{px4.string(), "-d", "-i", n, "-w", workdir.string(),
                               build.data.string()},
      options);
  return SitlProcess(Autopilot::Px4, std::move(slot), console, std::move(child));
}

SitlProcess SitlProcess::start_px4_hil(const FirmwareBuild& build, InstanceSlot slot,
                                       const fs::path& workdir, const FirmwareParams& params) {
  fs::create_directories(workdir);
  // A fresh start: parameters of an earlier run would override the airframe's.
  std::error_code ignored;
  fs::remove(workdir / "parameters.bson", ignored);
  fs::remove(workdir / "parameters_backup.bson", ignored);
  fs::remove(workdir / "dataman", ignored);
  const fs::path console = workdir / "console.log";
  process::SpawnOptions options = spawn_options(console);
  // PX4_SIMULATOR and PX4_SIM_MODEL empty: SYS_AUTOSTART alone picks simulator_mavlink.
  options.extra_env = {std::string("PX4_SYS_AUTOSTART=") + kPx4HilQuadAirframe,
                       "PX4_SIMULATOR=", "PX4_SIM_MODEL="};
  for (const auto& [name, value] : params)
    options.extra_env.push_back("PX4_PARAM_" + name + "=" + value);
  const std::string n = std::to_string(slot.instance());
  const fs::path px4 = link_px4_commands(build, workdir);
  auto child = std::make_unique<process::ChildProcess>(
      std::vector<std::string>{px4.string(), "-d", "-i", n, "-w", workdir.string(),
                               build.data.string()},
      options);
  return SitlProcess(Autopilot::Px4, std::move(slot), console, std::move(child));
}

SitlProcess SitlProcess::start_arducopter(const FirmwareBuild& build, InstanceSlot slot,
                                          const fs::path& workdir, const FirmwareParams& params) {
  return start_arducopter_model(build, std::move(slot), workdir, params, "quad");
}

SitlProcess SitlProcess::start_arducopter_json(const FirmwareBuild& build, InstanceSlot slot,
                                               const fs::path& workdir,
                                               const FirmwareParams& params) {
  return start_arducopter_model(build, std::move(slot), workdir, params, "JSON:127.0.0.1");
}

SitlProcess SitlProcess::start_arducopter_model(const FirmwareBuild& build, InstanceSlot slot,
                                                const fs::path& workdir,
                                                const FirmwareParams& params,
                                                const std::string& model) {
  fs::create_directories(workdir);
  const int n = slot.instance();
  const fs::path ours = workdir / "cover.parm";
  write_arducopter_params(ours, params, n + 1);
  const fs::path console = workdir / "console.log";
  // ArduPilot SITL writes its eeprom, logs and terrain into its working directory: a shell
  // enters it and becomes the firmware (exec: the same pid, the same process group).
  std::vector<std::string> argv{"/bin/sh",
                                "-c",
                                "cd \"$0\" && exec \"$@\"",
                                workdir.string(),
                                build.binary.string(),
                                "--model",
                                model,
                                "--speedup",
                                "1",
                                "-I",
                                std::to_string(n),
                                "--sysid",
                                std::to_string(n + 1),
                                "-w",
                                "--home",
                                kArduCopterHome,
                                "--defaults",
                                build.data.string() + "," + ours.string(),
                                "--serial0",
                                "tcp:0",
                                "--serial1",
                                "udpclient:127.0.0.1:" + std::to_string(companion_port(n))};
  auto child = std::make_unique<process::ChildProcess>(argv, spawn_options(console));
  return SitlProcess(Autopilot::ArduPilot, std::move(slot), console, std::move(child));
}

SitlProcess::~SitlProcess() {
  if (child_) stop();
}

bool SitlProcess::running() {
  if (!child_ || exit_code_) return false;
  if (const auto code = child_->wait(std::chrono::milliseconds(0))) {
    exit_code_ = code;
    return false;
  }
  return true;
}

int SitlProcess::stop(std::chrono::milliseconds grace) {
  if (!child_) return -1;
  if (!exit_code_) {
    const pid_t group = child_->pid();
    ::kill(-group, SIGTERM);
    exit_code_ = child_->wait(grace);
    if (!exit_code_) {
      // PX4 blocked in its simulator wait ignores SIGTERM: the whole group goes.
      ::kill(-group, SIGKILL);
      exit_code_ = child_->terminate(std::chrono::seconds(5), SIGKILL);
    }
  }
  if (firmware_ == Autopilot::Px4) remove_px4_tmp_files();
  return *exit_code_;
}

void SitlProcess::remove_px4_tmp_files() const {
  // Paths PX4's POSIX main and daemon fix (main.cpp LOCK_FILE_PATH, sock_protocol.cpp); our
  // instance number is held, and its process is gone, so they are ours to remove.
  const std::string n = std::to_string(instance());
  std::error_code ignored;
  fs::remove("/tmp/px4_lock-" + n, ignored);
  fs::remove("/tmp/px4-sock-" + n, ignored);
}

}  // namespace cover::firmware
