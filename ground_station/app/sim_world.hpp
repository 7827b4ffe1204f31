#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cover/shm/seqlock_reader.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover::ground_station {

// The simulator's world poses for the page's world frame: a simulated fleet has a ground
// truth that a real one lacks (a real fleet's page shows the UGV frames, from the relative
// states). Read from the world segment cover-sim shares on this host
// (/cover_sim_d<domain>_<run id>, as the UGV agents read their IMU), opened when it appears
// and again when its simulator is replaced; no segment, no world frame.
class SimWorld {
 public:
  SimWorld(int dds_domain, std::string run_id);
  SimWorld(const SimWorld&) = delete;
  SimWorld& operator=(const SimWorld&) = delete;

  // {"time_s", "ugvs": [{"position_m": [x, y, z], "yaw_rad"}], "uavs": [{"position_m",
  // "attitude_wxyz"}]}, or null when no simulator's world is readable.
  nlohmann::json json();

 private:
  bool reader_ready();

  std::string segment_;
  std::optional<shm::SeqlockReader<sim::SharedWorld>> reader_;
  std::unique_ptr<sim::SharedWorld> copy_ = std::make_unique<sim::SharedWorld>();
  std::chrono::steady_clock::time_point next_open_{};
  // The last world read, sent again when a read fails: the simulator rewrites its whole
  // segment (IMU rings included) hundreds of times a second, and a loaded reader's copy can
  // overlap a write every time it tries (SeqlockReader::kMaxCopies); the page would lose its
  // world frame for that state row.
  nlohmann::json last_;
  std::chrono::steady_clock::time_point last_read_{};
};

}  // namespace cover::ground_station
