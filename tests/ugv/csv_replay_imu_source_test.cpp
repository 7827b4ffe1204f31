#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "cover/ugv/csv_replay_imu_source.hpp"
#include "ugv_test_support.hpp"

namespace {

using cover::test::write_temp_file;
using cover::ugv::CsvFormatError;
using cover::ugv::CsvReplayImuSource;
using cover::ugv::ImuSample;
using cover::ugv::ImuSourceState;
using cover::ugv::parse_imu_csv;
using namespace std::chrono_literals;

const std::string kHeader = "stamp_s,fx_m_s2,fy_m_s2,fz_m_s2,wx_rad_s,wy_rad_s,wz_rad_s\n";

// The message of the CsvFormatError that parsing `text` raises ("" if none).
std::string parse_error(const std::string& name, const std::string& text) {
  try {
    parse_imu_csv(write_temp_file(name, text));
  } catch (const CsvFormatError& e) {
    return e.what();
  }
  return "";
}

TEST(CsvReplayImuSource, ParsesAGoodFileWithCommentsAndPassesNanThrough) {
  const std::string path =
      write_temp_file("good.csv", "# logged on the bench\n" + kHeader +
                                      "0.000, 0.1, 0.2, 9.81, 0.01, 0.02, 0.03\n"
                                      "\n"
                                      "# a gap in the log\n"
                                      "0.005,-1e-3,0,9.8,0,0,-0.5\n"
                                      "0.010,nan,0,9.8,0,0,0\n");
  const std::vector<ImuSample> samples = parse_imu_csv(path);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(samples[0].stamp_s, 0.0);
  EXPECT_EQ(samples[0].specific_force_m_s2, Eigen::Vector3d(0.1, 0.2, 9.81));
  EXPECT_EQ(samples[0].angular_velocity_rad_s, Eigen::Vector3d(0.01, 0.02, 0.03));
  EXPECT_EQ(samples[1].stamp_s, 0.005);
  EXPECT_EQ(samples[1].specific_force_m_s2.x(), -1e-3);
  EXPECT_EQ(samples[1].angular_velocity_rad_s.z(), -0.5);
  EXPECT_TRUE(std::isnan(samples[2].specific_force_m_s2.x()));
}

TEST(CsvReplayImuSource, ReadsTheOptionalWheelSpeedColumn) {
  const std::string header =
      "stamp_s,fx_m_s2,fy_m_s2,fz_m_s2,wx_rad_s,wy_rad_s,wz_rad_s,wheel_speed_m_s\n";
  const std::vector<ImuSample> samples =
      parse_imu_csv(write_temp_file("wheel.csv", header + "0.000,0,0.4,9.81,0,0,0.5,0.8\n"
                                                          "0.005,0,0.4,9.81,0,0,0.5,\n"
                                                          "0.010,0,0.4,9.81,0,0,0.5, -0.25 \n"
                                                          "0.015,0,0.4,9.81,0,0,0.5,nan\n"));
  ASSERT_EQ(samples.size(), 4u);
  EXPECT_EQ(samples[0].wheel_speed_m_s, std::optional<double>(0.8));
  EXPECT_FALSE(samples[1].wheel_speed_m_s.has_value());  // no reading with this sample
  EXPECT_EQ(samples[2].wheel_speed_m_s, std::optional<double>(-0.25));
  ASSERT_TRUE(samples[3].wheel_speed_m_s.has_value());  // the estimator rejects it
  EXPECT_TRUE(std::isnan(*samples[3].wheel_speed_m_s));
  // Without the column: no wheel speed at all; with it, 8 fields are required.
  EXPECT_FALSE(parse_imu_csv(write_temp_file("nowheel.csv", kHeader + "0,0,0,9.8,0,0,0\n"))[0]
                   .wheel_speed_m_s.has_value());
  const std::string short_line = parse_error("short.csv", header + "0.0,0,0,9.8,0,0,0\n");
  EXPECT_NE(short_line.find("short.csv:2: expected 8 columns, got 7"), std::string::npos)
      << short_line;
  const std::string bad = parse_error("badwheel.csv", header + "0.0,0,0,9.8,0,0,0,fast\n");
  EXPECT_NE(bad.find("badwheel.csv:2: 'fast' is not a number"), std::string::npos) << bad;
}

TEST(CsvReplayImuSource, NamesTheLineOfAMalformedFile) {
  const std::string wrong_columns = parse_error("cols.csv", kHeader +
                                                                "0.0,0,0,9.8,0,0,0\n"
                                                                "0.005,0,0,9.8,0,0\n");
  EXPECT_NE(wrong_columns.find("cols.csv:3: expected 7 columns, got 6"), std::string::npos)
      << wrong_columns;

  const std::string not_number = parse_error("num.csv", "# c\n" + kHeader + "0.0,0,x1,9.8,0,0,0\n");
  EXPECT_NE(not_number.find("num.csv:3: 'x1' is not a number"), std::string::npos) << not_number;

  const std::string trailing = parse_error("trail.csv", kHeader + "0.0,0,0,9.8,0,0,0,\n");
  EXPECT_NE(trailing.find("trail.csv:2: expected 7 columns, got 8"), std::string::npos) << trailing;

  const std::string stale = parse_error("stale.csv", kHeader +
                                                         "0.01,0,0,9.8,0,0,0\n"
                                                         "0.01,0,0,9.8,0,0,0\n");
  EXPECT_NE(stale.find("stale.csv:3: stamp_s is not after"), std::string::npos) << stale;

  const std::string nan_stamp = parse_error("nanstamp.csv", kHeader + "nan,0,0,9.8,0,0,0\n");
  EXPECT_NE(nan_stamp.find("nanstamp.csv:2: stamp_s is not finite"), std::string::npos);

  const std::string no_header = parse_error("nohead.csv", "0.0,0,0,9.8,0,0,0\n");
  EXPECT_NE(no_header.find("nohead.csv:1: expected the header line"), std::string::npos);

  EXPECT_THROW(CsvReplayImuSource("/nonexistent/imu.csv"), CsvFormatError);
}

TEST(CsvReplayImuSource, ReplaysEverySampleInOrderPacedAndEndsAtEof) {
  std::string text = kHeader;
  for (int i = 0; i < 40; ++i) {
    text += std::to_string(1.0 + 0.005 * i) + ",0,0,9.81,0,0," + std::to_string(i) + "\n";
  }
  CsvReplayImuSource source(write_temp_file("replay.csv", text), /*rate=*/1.0);
  EXPECT_EQ(source.sample_count(), 40u);
  std::vector<ImuSample> all;
  std::vector<ImuSample> batch;
  const auto start = std::chrono::steady_clock::now();
  while (source.status().state == ImuSourceState::Ok &&
         std::chrono::steady_clock::now() - start < 5s) {
    source.read(batch, 50ms);
    all.insert(all.end(), batch.begin(), batch.end());
  }
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(source.status().state, ImuSourceState::Ended);
  ASSERT_EQ(all.size(), 40u);
  for (int i = 0; i < 40; ++i) EXPECT_EQ(all[i].angular_velocity_rad_s.z(), i);
  // The last stamp is 195 ms after the first: real-time pacing cannot finish sooner.
  EXPECT_GE(elapsed, 190ms);
  EXPECT_EQ(source.read(batch, 10ms), 0u);
}

TEST(CsvReplayImuSource, ReplayRateSpeedsUpThePacing) {
  std::string text = kHeader;
  for (int i = 0; i < 201; ++i) text += std::to_string(0.01 * i) + ",0,0,9.81,0,0,0\n";
  CsvReplayImuSource source(write_temp_file("fast.csv", text), /*rate=*/10.0);
  std::vector<ImuSample> batch;
  std::size_t total = 0;
  const auto start = std::chrono::steady_clock::now();
  while (source.status().state == ImuSourceState::Ok &&
         std::chrono::steady_clock::now() - start < 10s) {
    total += source.read(batch, 50ms);
  }
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(total, 201u);
  EXPECT_GE(elapsed, 195ms);   // 2 s of stamps at 10x
  EXPECT_LT(elapsed, 1900ms);  // and clearly not real time
  EXPECT_THROW(CsvReplayImuSource(write_temp_file("rate.csv", text), 0.0), std::invalid_argument);
}

TEST(CsvReplayImuSource, AnEmptyReplayEndsAtOnce) {
  CsvReplayImuSource source(write_temp_file("empty.csv", "# nothing yet\n" + kHeader));
  EXPECT_EQ(source.status().state, ImuSourceState::Ended);
  std::vector<ImuSample> batch;
  EXPECT_EQ(source.read(batch, 10ms), 0u);
}

}  // namespace
