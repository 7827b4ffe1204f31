#include "cover/ugv/csv_replay_imu_source.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace cover::ugv {

namespace {

constexpr const char* kHeader = "stamp_s,fx_m_s2,fy_m_s2,fz_m_s2,wx_rad_s,wy_rad_s,wz_rad_s";
// The optional eighth column: wheel odometry, empty on lines without a reading.
constexpr const char* kWheelSpeedColumn = ",wheel_speed_m_s";
constexpr std::size_t kImuColumns = 7;

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(trim(field));
  // getline drops an empty last field ("1,2,"): count it, it is a wrong column count.
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// strtod accepts "nan" and "inf", which a logger may write for a faulty sample.
double parse_number(const std::string& field, const std::string& where) {
  const char* begin = field.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (field.empty() || end != begin + field.size()) {
    throw CsvFormatError(where + ": '" + field + "' is not a number");
  }
  return value;
}

ImuSample parse_line(const std::string& line, const std::string& where, std::size_t columns) {
  const std::vector<std::string> fields = split_fields(line);
  if (fields.size() != columns) {
    throw CsvFormatError(where + ": expected " + std::to_string(columns) + " columns, got " +
                         std::to_string(fields.size()));
  }
  double v[kImuColumns];
  for (std::size_t i = 0; i < kImuColumns; ++i) v[i] = parse_number(fields[i], where);
  ImuSample sample;
  sample.stamp_s = v[0];
  sample.specific_force_m_s2 = {v[1], v[2], v[3]};
  sample.angular_velocity_rad_s = {v[4], v[5], v[6]};
  if (columns > kImuColumns && !fields[kImuColumns].empty()) {
    sample.wheel_speed_m_s = parse_number(fields[kImuColumns], where);
  }
  return sample;
}

}  // namespace

std::vector<ImuSample> parse_imu_csv(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw CsvFormatError(path + ": cannot open the file");
  std::vector<ImuSample> samples;
  bool header_seen = false;
  std::size_t columns = kImuColumns;
  const std::string header_with_speed = std::string(kHeader) + kWheelSpeedColumn;
  std::string raw;
  for (int line_number = 1; std::getline(file, raw); ++line_number) {
    const std::string line = trim(raw);
    if (line.empty() || line.front() == '#') continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (!header_seen) {
      if (line == header_with_speed) {
        columns = kImuColumns + 1;
      } else if (line != kHeader) {
        throw CsvFormatError(where + ": expected the header line '" + std::string(kHeader) +
                             "' (optionally followed by '" + kWheelSpeedColumn + "')");
      }
      header_seen = true;
      continue;
    }
    ImuSample sample = parse_line(line, where, columns);
    // Pacing needs the stamps; a bad stamp is a broken file, not a sensor fault.
    if (!std::isfinite(sample.stamp_s)) throw CsvFormatError(where + ": stamp_s is not finite");
    if (!samples.empty() && sample.stamp_s <= samples.back().stamp_s) {
      throw CsvFormatError(where + ": stamp_s is not after the previous line's");
    }
    samples.push_back(sample);
  }
  if (!header_seen) throw CsvFormatError(path + ": no header line (empty file?)");
  return samples;
}

CsvReplayImuSource::CsvReplayImuSource(const std::string& path, double rate)
    : path_(path), rate_(rate) {
  if (!(std::isfinite(rate) && rate > 0.0)) {
    throw std::invalid_argument("replay rate must be a positive number");
  }
  samples_ = parse_imu_csv(path);
  if (samples_.empty()) {
    status_.state = ImuSourceState::Ended;
    status_.detail = "no samples in " + path_;
  }
}

std::chrono::steady_clock::time_point CsvReplayImuSource::due_time(std::size_t index) const {
  const double offset_s = (samples_[index].stamp_s - samples_.front().stamp_s) / rate_;
  return start_time_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(offset_s));
}

std::size_t CsvReplayImuSource::read(std::vector<ImuSample>& out,
                                     std::chrono::milliseconds timeout) {
  out.clear();
  if (status_.state != ImuSourceState::Ok) return 0;
  if (!started_) {
    started_ = true;
    start_time_ = std::chrono::steady_clock::now();
  }
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  // Like a device: sleep until the next sample is due (or the timeout), then hand over
  // everything due by then.
  std::this_thread::sleep_until(std::min(due_time(next_), give_up));
  const auto now = std::chrono::steady_clock::now();
  while (next_ < samples_.size() && due_time(next_) <= now) out.push_back(samples_[next_++]);
  if (next_ == samples_.size()) {
    status_.state = ImuSourceState::Ended;
    status_.detail = "replayed all " + std::to_string(samples_.size()) + " samples of " + path_;
  }
  return out.size();
}

}  // namespace cover::ugv
