#include "sim_world.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "cover/shm/segment_name.hpp"

namespace cover::ground_station {
namespace {

// A missing segment is looked for again this often: opening is a failed shm_open, cheap,
// but not at the page's 10 Hz for a fleet that has no simulator.
constexpr std::chrono::seconds kReopenPeriod{1};
// The last world stands in for failed reads this long; older, the world is gone.
constexpr std::chrono::seconds kLastWorldValid{2};

nlohmann::json xyz(const sim::Vec3& v) {
  return nlohmann::json::array({v.x, v.y, v.z});
}

}  // namespace

SimWorld::SimWorld(int dds_domain, std::string run_id)
    : segment_(shm::segment_name(dds_domain, run_id)) {}

bool SimWorld::reader_ready() {
  if (reader_ && reader_->writer_alive()) return true;
  reader_.reset();
  const auto now = std::chrono::steady_clock::now();
  if (now < next_open_) return false;
  next_open_ = now + kReopenPeriod;
  try {
    reader_.emplace(shm::SeqlockReader<sim::SharedWorld>::open(
        segment_, sim::kWorldSegmentLayoutVersion, std::chrono::milliseconds(0)));
    spdlog::info("world frame: reading the simulator's world {}", segment_);
    return true;
  } catch (const std::runtime_error&) {
    return false;  // no simulator on this host (yet): the page offers the UGV frames
  }
}

nlohmann::json SimWorld::json() {
  if (!reader_ready()) return nullptr;
  const auto now = std::chrono::steady_clock::now();
  if (!reader_->read(*copy_)) return now - last_read_ < kLastWorldValid ? last_ : nullptr;
  last_read_ = now;
  const sim::SharedWorld& w = *copy_;
  nlohmann::json ugvs = nlohmann::json::array();
  for (int k = 0; k < std::clamp(w.ugv_count, 0, sim::kMaxUgvs); ++k) {
    ugvs.push_back({{"position_m", xyz(w.ugvs[k].position_m)}, {"yaw_rad", w.ugvs[k].yaw_rad}});
  }
  nlohmann::json uavs = nlohmann::json::array();
  for (int u = 0; u < std::clamp(w.uav_count, 0, static_cast<int>(sim::kMaxUavs)); ++u) {
    const auto& s = w.uavs[u].state;
    uavs.push_back({{"position_m", xyz(s.position_m)},
                    {"attitude_wxyz", {s.attitude.w, s.attitude.x, s.attitude.y, s.attitude.z}}});
  }
  last_ = {{"time_s", w.time_s}, {"ugvs", std::move(ugvs)}, {"uavs", std::move(uavs)}};
  return last_;
}

}  // namespace cover::ground_station
