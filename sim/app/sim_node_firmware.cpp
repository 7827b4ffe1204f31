// SimNode with real firmware (cover-sim --firmware px4|ardupilot): the firmware's physics
// links connect before the first tick, and the world waits (its UGVs still) until every
// firmware's estimator has aligned on its deck, as its bridge reports (cover/uav/<u>/fc).
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
  return settle_firmware();
}

// Before the first tick: the firmware alone on its still deck (the world's clock stands,
// the firmware's runs, as fast as it answers in lockstep, at its own pace in realtime) until
// every firmware's bridge reports a valid attitude estimate.
bool SimNode::settle_firmware() {
  spdlog::info(
      "the world waits, its UGVs still, until every firmware's estimator has aligned "
      "(PX4 aligns only below 15 deg/s; at most {:.0f} s of firmware time)",
      params_.firmware_align_timeout_s);
  const auto wall_start = std::chrono::steady_clock::now();
  while (true) {
    if (process::ShutdownSignal::requested()) return false;
    const int waiting_for = first_unaligned_uav();
    const double firmware_s = fleet_.firmware_time_s(waiting_for < 0 ? 0 : waiting_for);
    if (waiting_for < 0) {
      const double wall_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
      spdlog::info(
          "every firmware's estimator has aligned after {:.2f} s of firmware time "
          "({:.2f} s wall): the world starts, the UGVs move",
          firmware_s, wall_s);
      return true;
    }
    if (firmware_s >= params_.firmware_align_timeout_s) {
      spdlog::error(
          "UAV {}'s {} firmware has not reported a valid attitude estimate after "
          "{:.0f} s of firmware time (its bridge, cover-fc-bridge --id {}, reports it "
          "on cover/uav/{}/fc)",
          waiting_for, fleet_.firmware_name(), firmware_s, waiting_for, waiting_for);
      return false;
    }
    fleet_.settle_firmware();
  }
}

int SimNode::first_unaligned_uav() const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (int u = 0; u < fleet_.uav_count(); ++u) {
    if (!mailboxes_[u].estimator_ok) return u;
  }
  return -1;
}

void SimNode::on_fc_state(int u, const msg::FcState& state) {
  std::lock_guard<std::mutex> lock(mutex_);
  Mailbox& box = mailboxes_[u];
  box.estimator_ok = state.estimator_reported && state.estimator_ok;
  box.firmware_landing = state.mode == msg::FcMode::FC_MODE_LAND;
}

}  // namespace cover::sim
