#pragma once

#include <memory>
#include <string>

#include "cover/ugv/imu_source.hpp"
#include "ugv_agent_params.hpp"

namespace cover::ugv {

// What the command line says about the IMU source.
struct SourceOptions {
  std::string kind = "sim";  // one of source_kinds()
  int ugv_id = 0;
  int dds_domain = 0;  // sim: part of the segment name
  std::string run_id = "default";
  std::string csv_path;
  double replay_rate = 1.0;
  std::string mavlink_url;                  // mavlink: the autopilot's link (MAVSDK's URL forms)
  std::string mavlink_stamp = "autopilot";  // mavlink: autopilot | receive
};

// "sim|csv|mavlink": for --help and the --source check. A new device driver adds its kind here and
// a branch in make_source (see ugv_agent/README.md, "Adding a device").
const char* source_kinds();
bool is_source_kind(const std::string& kind);

// Opens the source; throws std::runtime_error (or CsvFormatError) when it cannot: the
// segment did not appear within segment_wait_s, a malformed CSV file, a missing device, a
// MAVLink port already taken (std::invalid_argument for a malformed URL).
std::unique_ptr<ImuSource> make_source(const SourceOptions& options, const UgvAgentParams& params);

}  // namespace cover::ugv
