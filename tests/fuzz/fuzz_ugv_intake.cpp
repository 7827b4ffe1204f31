// The UGV agent's sample intake: its raw IMU (and wheel odometry) through the filter and
// the speed estimator it publishes from (cover-ugv-agent), and the CSV replay source's
// parser. Contract: the CSV parser returns strictly increasing finite stamps or throws
// CsvFormatError; the filter's output is finite and in range whatever it is fed, rejected
// samples leave it unchanged, and the speed estimate is finite and within max_speed_m_s.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cover/ugv/csv_replay_imu_source.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/speed_estimator.hpp"
#include "fuzz_input.hpp"

namespace {

using cover::fuzz::FuzzInput;
using cover::fuzz::require;
namespace ugv = cover::ugv;

void csv(const std::string& text) {
  static const std::string path = (std::filesystem::temp_directory_path() /
                                   ("cover-fuzz-imu-" + std::to_string(getpid()) + ".csv"))
                                      .string();
  static const bool cleanup = [] {
    std::atexit([] { std::filesystem::remove(path); });
    return true;
  }();
  (void)cleanup;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  try {
    const auto samples = ugv::parse_imu_csv(path);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      require(std::isfinite(samples[i].stamp_s), "CSV: a non-finite stamp");
      require(i == 0 || samples[i].stamp_s > samples[i - 1].stamp_s, "CSV: stamps not increasing");
    }
  } catch (const ugv::CsvFormatError& e) {
    require(std::string(e.what()).find(':') != std::string::npos, "CSV: error names no line");
  } catch (const std::exception& e) {
    cover::fuzz::violated(std::string("CSV: not a CsvFormatError: ") + e.what());
  }
}

Eigen::Vector3d vec(FuzzInput& in) {
  return {in.real(), in.real(), in.real()};
}

void stream(FuzzInput& in) {
  const ugv::ImuFilterParams params;
  const ugv::SpeedEstimatorParams speed_params;
  ugv::ImuFilter filter(params);
  ugv::SpeedEstimator speed(speed_params);
  double t = 0.0;
  while (!in.empty()) {
    ugv::ImuSample s;
    const std::uint8_t timing = in.byte() % 8;
    t = timing == 0 ? in.real() : timing == 1 ? t - 0.01 : t + 0.005;
    s.stamp_s = t;
    s.specific_force_m_s2 = in.byte() % 2 ? vec(in) : Eigen::Vector3d(0.0, in.real(), 9.81);
    s.angular_velocity_rad_s = in.byte() % 2 ? vec(in) : Eigen::Vector3d(0.0, 0.0, in.real());
    if (in.byte() % 2) s.wheel_speed_m_s = in.real();
    const ugv::FilteredImu before = filter.output();
    const bool had_output = filter.has_output();
    const ugv::ImuFilterStatus status = filter.update(s);
    if (!ugv::accepted(status)) {
      require(filter.has_output() == had_output, "a rejected sample changed the filter state");
      if (had_output) {
        require(filter.output().specific_force_m_s2 == before.specific_force_m_s2 &&
                    filter.output().angular_velocity_rad_s == before.angular_velocity_rad_s,
                "a rejected sample changed the output");
      }
    } else {
      const ugv::FilteredImu& out = filter.output();
      require(std::isfinite(out.stamp_s) && out.specific_force_m_s2.allFinite() &&
                  out.angular_velocity_rad_s.allFinite() &&
                  out.angular_acceleration_rad_s2.allFinite(),
              "the filter output is not finite");
      require(out.specific_force_m_s2.norm() <= params.max_specific_force_m_s2 * 1.0001 &&
                  out.angular_velocity_rad_s.norm() <= params.max_angular_velocity_rad_s * 1.0001,
              "the filter output is beyond the sensor's full scale");
      speed.update_imu(out);
    }
    if (s.wheel_speed_m_s) speed.update_odometry({s.stamp_s, *s.wheel_speed_m_s});
    const ugv::SpeedEstimate& e = speed.estimate();
    require(std::isfinite(e.speed_m_s) && std::isfinite(e.stamp_s), "speed estimate not finite");
    require(!e.valid() || std::abs(e.speed_m_s) <= speed_params.max_speed_m_s * 1.0001,
            "speed estimate above max_speed_m_s");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  if (in.byte() % 2) {
    csv(in.rest());
  } else {
    stream(in);
  }
  return 0;
}
