// SimNode with real firmware (cover-sim --firmware px4|ardupilot): the firmware's physics
// links connect before the first tick, and the UGVs hold still until every firmware's
// estimator has aligned on its deck, as its bridge reports (cover/uav/<u>/fc).
#include <spdlog/spdlog.h>

#include <chrono>

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "sim_node.hpp"

namespace cover::sim {

namespace {
using namespace std::chrono_literals;
}  // namespace

bool SimNode::wait_for_firmware() {
  const auto deadline =
      std::chrono::steady_clock::now() + clock::to_milliseconds(params_.startup_timeout_s);
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    firmware_link::FirmwareLink& link = fleet_.firmware_link(u);
    spdlog::info("UAV {}: waiting for its {} firmware: {}", u, fleet_.firmware_name(),
                 link.describe());
    while (!link.wait_for_firmware(100ms)) {
      if (process::ShutdownSignal::requested()) return false;
      if (std::chrono::steady_clock::now() >= deadline) {
        spdlog::error(
            "UAV {}: no {} firmware on {} after {:.0f} s (is it started? "
            "config/launch/scenario2_*_sitl.yaml starts it)",
            u, fleet_.firmware_name(), link.describe(), params_.startup_timeout_s);
        return false;
      }
    }
    spdlog::info("UAV {}: {} firmware connected", u, fleet_.firmware_name());
  }
  fleet_.hold_ugvs(true);
  spdlog::info(
      "the UGVs hold still until every firmware's estimator has aligned (PX4 aligns "
      "only below 15 deg/s; at most {:.0f} s)",
      params_.firmware_align_timeout_s);
  return true;
}

void SimNode::on_fc_state(int u, const msg::FcState& state) {
  std::lock_guard<std::mutex> lock(mutex_);
  Mailbox& box = mailboxes_[u];
  box.estimator_ok = state.estimator_reported && state.estimator_ok;
  box.firmware_armed = state.armed;
}

bool SimNode::release_ugvs_when_aligned() {
  if (!fleet_.ugvs_held()) return true;
  const double t_s = fleet_.time_s();
  int waiting_for = -1;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (int u = 0; u < fleet_.uav_count() && waiting_for < 0; ++u) {
      if (!mailboxes_[u].estimator_ok) waiting_for = u;
    }
  }
  if (waiting_for < 0) {
    spdlog::info("every firmware's estimator has aligned at t = {:.2f} s: the UGVs start", t_s);
    fleet_.hold_ugvs(false);
    return true;
  }
  if (t_s < params_.firmware_align_timeout_s) return true;
  spdlog::error(
      "UAV {}'s {} firmware has not reported a valid attitude estimate after {:.0f} s "
      "(its bridge, cover-fc-bridge --id {}, reports it on cover/uav/{}/fc)",
      waiting_for, fleet_.firmware_name(), t_s, waiting_for, waiting_for);
  return false;
}

}  // namespace cover::sim
