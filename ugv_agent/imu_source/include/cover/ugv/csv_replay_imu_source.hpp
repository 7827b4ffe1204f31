#pragma once

#include <chrono>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "cover/ugv/imu_source.hpp"

namespace cover::ugv {

// A CSV file is malformed: the message names the file and the line ("imu.csv:12: ...").
class CsvFormatError : public std::runtime_error {
 public:
  explicit CsvFormatError(const std::string& what) : std::runtime_error(what) {}
};

// Parses an IMU CSV file (format: docs/imu_csv.md). Throws CsvFormatError naming the line
// (wrong column count, a field that is not a number, a stamp not finite or not strictly
// increasing), or when the file cannot be opened. NaN / inf measurement values are kept:
// rejecting them is the filter's job.
std::vector<ImuSample> parse_imu_csv(const std::string& path);

// Replays a parsed IMU CSV file, paced on the host's steady clock: sample i is due
// (stamp_i - stamp_0) / rate after the first read. Ends (state Ended) after the last one.
// The whole file is parsed up front, so a malformed file fails before anything is sent.
class CsvReplayImuSource : public ImuSource {
 public:
  // `rate` > 0: 1 replays in real time, 10 ten times faster. Throws CsvFormatError, or
  // std::invalid_argument for a rate that is not a positive number.
  explicit CsvReplayImuSource(const std::string& path, double rate = 1.0);

  std::size_t read(std::vector<ImuSample>& out, std::chrono::milliseconds timeout) override;
  std::string describe() const override { return "csv:" + path_; }
  ImuSourceStatus status() const override { return status_; }

  std::size_t sample_count() const { return samples_.size(); }

 private:
  std::chrono::steady_clock::time_point due_time(std::size_t index) const;

  std::string path_;
  double rate_;
  std::vector<ImuSample> samples_;
  std::size_t next_ = 0;
  bool started_ = false;
  std::chrono::steady_clock::time_point start_time_;
  ImuSourceStatus status_;
};

}  // namespace cover::ugv
