#include "security_cli.hpp"

#include <CLI/CLI.hpp>

namespace cover::cli {

SecurityCli::SecurityCli(CLI::App& app) {
  auto* security = app.add_subcommand("security", "Make and check DDS-Security fleet directories");
  security->require_subcommand(1);
  init_ = security->add_subcommand(
      "init", "Make a CA, one identity per process, signed governance and permissions");
  init_->add_option("dir", init_request_.directory, "new fleet directory")->required();
  init_->add_option("--ugvs", init_request_.fleet.ugvs, "UGV agents")->capture_default_str();
  init_->add_option("--uavs", init_request_.fleet.uavs, "UAV agents")->capture_default_str();
  init_->add_option("--ground-stations", init_request_.fleet.ground_stations, "ground stations")
      ->capture_default_str();
  init_->add_option("--days", init_request_.days, "validity of every certificate and permission")
      ->capture_default_str();
  init_
      ->add_option("--vendor", init_request_.vendor,
                   "the DDS vendor every process of the fleet runs: fastdds | cyclone")
      ->capture_default_str();
  init_->footer(
      "Exit: 0 made and checked, 2 a bad request or an existing directory, 3 openssl failed.");
  check_ = security->add_subcommand(
      "check", "Per identity: what it may publish and subscribe, when it expires");
  check_->add_option("dir", check_directory_, "fleet directory")->required();
  check_->add_flag("--json", check_json_, "one JSON object");
  check_->add_option("--warning-days", check_warning_days_,
                     "fail (exit 4) when the CA or an identity expires within N days "
                     "(default: security.expiry_warning_days of config/dds.yaml)");
  check_->footer(
      "Exit: 0 the CA and every identity valid beyond the warning window, 1 one broken, "
      "expired or mis-signed, 2 DIR is not a fleet directory, 4 all valid but one (or the CA) "
      "expires within the window.");
}

bool SecurityCli::chosen() const {
  return init_->parsed() || check_->parsed();
}

int SecurityCli::run() {
  if (init_->parsed()) return security_init(init_request_);
  return security_check(check_directory_, check_json_, check_warning_days_);
}

}  // namespace cover::cli
