#pragma once

#include <string>
#include <vector>

#include "cover/dds/cli_options.hpp"
#include "cover/recording/player.hpp"
#include "cover/recording/recorder.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace cover::cli {

// Exit codes of `cover record`, `cover bag info` and `cover play`.
inline constexpr int kBagOk = 0;           // recorded and closed / file complete / played
inline constexpr int kBagDamaged = 1;      // file cut or corrupt: what was readable was used
inline constexpr int kBagUsage = 2;        // usage, or not an MCAP file at all
inline constexpr int kBagWriteFailed = 3;  // record: the file could not be written

// The flight recorder's commands, with ros2 bag's conventions:
//   cover record [-o FILE.mcap] [--topics GLOB...] [--compression zstd|lz4|none] [--duration S]
//   cover bag info FILE [--json]
//   cover play FILE [--rate X] [--topics GLOB...] [--start S]
class RecordCommands {
 public:
  explicit RecordCommands(CLI::App& app);
  bool chosen() const;
  int run();

 private:
  int record();
  int info() const;
  int play();

  CLI::App* record_ = nullptr;
  CLI::App* info_ = nullptr;
  CLI::App* play_ = nullptr;
  recording::RecorderOptions record_options_;
  std::string compression_ = "zstd";
  double duration_s_ = 0.0;
  double chunk_duration_s_ = 1.0;
  std::string bag_path_;
  bool json_ = false;
  recording::PlayOptions play_options_;
  dds::DdsCliOptions record_dds_;
  dds::DdsCliOptions play_dds_;
};

}  // namespace cover::cli
