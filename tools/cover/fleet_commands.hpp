#pragma once

#include <string>

#include "cover/dds/cli_options.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/recording/fleet_topics.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace cover::cli {

// Exit codes of `cover fleet`.
inline constexpr int kFleetHeard = 0;  // something heard (--watch: stopped by SIGINT/SIGTERM)
inline constexpr int kFleetNothing =
    3;  // nothing heard on the domain: what was listened for printed
inline constexpr int kFleetInterrupted = 130;  // SIGINT/SIGTERM before the first listing

// `cover fleet [--watch] [--json]`: every vehicle and process heard on the domain, as
// QGroundControl's vehicle list: UAV agents (cover/uav/<u>/status), flight-controller
// bridges (cover/uav/<u>/fc), UGV agents (cover/ugv/<k>/status), the simulator
// (cover/sim/clock), every process in the clock exchange (cover/time/request|reply: the
// task manager's only periodic message, and the hosts) and the task manager's answer to a
// query of its tasks. Needs no task id.
class FleetListener;
class ManagerClient;

class FleetCommand {
 public:
  explicit FleetCommand(CLI::App& app);
  bool chosen() const;
  int run();

 private:
  // How long a listing listens: at least min_s, then until every process heard is
  // described, at most bound_s.
  struct Window {
    double min_s = 0.0;
    double bound_s = 0.0;
  };
  static bool listen(FleetListener& listener, ManagerClient& manager, const Window& window);
  Window first_window(const dds::ParticipantOptions& options) const;

  CLI::App* fleet_ = nullptr;
  double listen_s_ = 1.5;
  bool watch_ = false;
  bool json_ = false;
  recording::FleetSize size_;
  dds::DdsCliOptions dds_;
};

}  // namespace cover::cli
