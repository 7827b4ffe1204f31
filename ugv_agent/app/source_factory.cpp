#include "source_factory.hpp"

#include <chrono>
#include <stdexcept>

#include "cover/shm/segment_name.hpp"
#include "cover/ugv/csv_replay_imu_source.hpp"
#include "cover/ugv/mavlink_imu_source.hpp"
#include "cover/ugv/sim_shm_imu_source.hpp"

namespace cover::ugv {

const char* source_kinds() {
  return "sim|csv|mavlink";
}

bool is_source_kind(const std::string& kind) {
  return kind == "sim" || kind == "csv" || kind == "mavlink";
}

std::unique_ptr<ImuSource> make_source(const SourceOptions& options, const UgvAgentParams& params) {
  if (options.kind == "sim") {
    const auto wait = std::chrono::milliseconds(static_cast<long>(params.segment_wait_s * 1000.0));
    return std::make_unique<SimShmImuSource>(
        cover::shm::segment_name(options.dds_domain, options.run_id), options.ugv_id, wait);
  }
  if (options.kind == "csv") {
    return std::make_unique<CsvReplayImuSource>(options.csv_path, options.replay_rate);
  }
  if (options.kind == "mavlink") {
    const auto stamp = parse_mavlink_stamp(options.mavlink_stamp);
    if (!stamp) {
      throw std::invalid_argument("--mavlink-stamp must be autopilot or receive, not '" +
                                  options.mavlink_stamp + "'");
    }
    return std::make_unique<MavlinkImuSource>(options.mavlink_url, *stamp);
  }
  // Register a new source kind above (and in is_source_kind / source_kinds).
  throw std::runtime_error("unknown IMU source '" + options.kind + "' (expected " + source_kinds() +
                           ")");
}

}  // namespace cover::ugv
