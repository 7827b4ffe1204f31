#include "ugv_agent.hpp"

#include <spdlog/spdlog.h>

#include <chrono>

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::ugv {

namespace {

using cover::clock::monotonic_ns;

// Bounds how long a shutdown request or a stalled device goes unnoticed.
constexpr std::chrono::milliseconds kReadTimeout{10};
// A device silent for this long has its last sample published again (see
// ImuPublisher::republish_last): a simulator in lockstep waits for the agents.
constexpr std::int64_t kRepeatAfterNs = 20'000'000;
constexpr std::int64_t kLogIntervalNs = 1'000'000'000;

// Counts an event and says whether a line is due (at most one per kLogIntervalNs).
template <typename Log>
bool due(Log& log, std::uint64_t count, std::int64_t now_ns) {
  log.pending += count;
  if (now_ns - log.last_ns < kLogIntervalNs) return false;
  log.last_ns = now_ns;
  return true;
}

}  // namespace

UgvAgent::UgvAgent(const UgvAgentParams& params, std::unique_ptr<ImuSource> source,
                   ImuPublisher& publisher)
    : params_(params),
      source_(std::move(source)),
      publisher_(publisher),
      pipeline_(params.imu_filter, params.speed_estimator),
      health_monitor_(params.nominal_imu_rate_hz),
      source_name_(source_->describe()) {}

int UgvAgent::run() {
  publish_status();
  while (!cover::process::ShutdownSignal::requested()) {
    source_->read(batch_, kReadTimeout);
    const std::int64_t now_ns = monotonic_ns();
    for (const ImuSample& sample : batch_) handle(sample, now_ns);
    if (!batch_.empty()) {
      last_publish_ns_ = now_ns;
    } else if (accepted_ > 0 && now_ns - last_publish_ns_ >= kRepeatAfterNs) {
      publisher_.republish_last();
      last_publish_ns_ = now_ns;
    }
    const ImuSourceStatus status = source_->status();
    if (status.lost_samples > lost_reported_) log_lost_samples(status.lost_samples, now_ns);
    update_health(now_ns);
    if (status.state != ImuSourceState::Ok) return finish(status);
  }
  spdlog::info("shutdown requested: {} samples published, {} rejected", accepted_, rejected_);
  publish_status();
  publisher_.flush_status(std::chrono::milliseconds(500));
  return kExitOk;
}

void UgvAgent::handle(const ImuSample& sample, std::int64_t now_ns) {
  const UgvSensorResult result = pipeline_.update(sample);
  if (sample.wheel_speed_m_s && result.odometry_status != SpeedSampleStatus::Accepted) {
    ++odometry_rejected_;
    log_odometry_rejection(result.odometry_status, now_ns);
  }
  const ImuFilterStatus status = result.imu_status;
  const bool ok = accepted(status);
  health_monitor_.on_sample(now_ns, ok);
  if (!ok) {
    ++rejected_;
    log_rejection(status, now_ns);
    return;
  }
  if (accepted_ == 0) {
    spdlog::info("first sample: stamp {:.6f} s", sample.stamp_s);
  } else if (status == ImuFilterStatus::RestartedAfterGap) {
    spdlog::warn("filter restarted: {:.3f} s since the previous sample",
                 sample.stamp_s - last_stamp_s_);
  }
  ++accepted_;
  last_stamp_s_ = sample.stamp_s;
  log_speed_source(pipeline_.speed().estimate());
  publisher_.publish_imu(pipeline_.filter().output(), pipeline_.speed().estimate());
}

void UgvAgent::log_odometry_rejection(SpeedSampleStatus status, std::int64_t now_ns) {
  if (!due(odometry_log_, 1, now_ns)) return;
  spdlog::warn(
      "{} wheel odometry sample(s) rejected since the last report (latest: {}); {} in total",
      odometry_log_.pending, to_string(status), odometry_rejected_);
  odometry_log_.pending = 0;
}

// The source changes at most a few times a run (a UGV that starts or stops turning).
void UgvAgent::log_speed_source(const SpeedEstimate& speed) {
  if (speed.source == logged_speed_source_) return;
  logged_speed_source_ = speed.source;
  spdlog::info("speed estimate: {} ({:.3f} m/s)", to_string(speed.source), speed.speed_m_s);
}

void UgvAgent::log_rejection(ImuFilterStatus status, std::int64_t now_ns) {
  if (!due(rejections_log_, 1, now_ns)) return;
  spdlog::warn("{} sample(s) rejected since the last report (latest: {}); {} in total",
               rejections_log_.pending, to_string(status), rejected_);
  rejections_log_.pending = 0;
}

void UgvAgent::log_lost_samples(std::uint64_t lost_total, std::int64_t now_ns) {
  const std::uint64_t new_losses = lost_total - lost_reported_;
  lost_reported_ = lost_total;
  if (!due(lost_log_, new_losses, now_ns)) return;
  spdlog::warn("{} sample(s) lost (the device overran this reader); {} in total", lost_log_.pending,
               lost_total);
  lost_log_.pending = 0;
}

void UgvAgent::update_health(std::int64_t now_ns) {
  const ImuHealth health = health_monitor_.evaluate(now_ns);
  const bool changed = health.healthy != health_.healthy;
  health_ = health;
  if (changed) {
    spdlog::info("health: {} (IMU {:.1f} Hz of {:.1f} nominal, {} rejected in total)",
                 health.healthy ? "healthy" : "UNHEALTHY", health.imu_rate_hz,
                 params_.nominal_imu_rate_hz, rejected_);
  }
  if (changed || now_ns >= next_status_ns_) publish_status();
}

void UgvAgent::publish_status() {
  UgvStatusReport report;
  report.stamp_s = last_stamp_s_;
  report.source = source_name_;
  report.imu_rate_hz = health_.imu_rate_hz;
  report.healthy = health_.healthy;
  report.samples = accepted_;
  report.rejected_samples = rejected_;
  publisher_.publish_status(report);
  next_status_ns_ = monotonic_ns() + static_cast<std::int64_t>(1e9 / params_.status_rate_hz);
}

int UgvAgent::finish(const ImuSourceStatus& status) {
  const bool clean = status.state == ImuSourceState::Ended;
  if (clean) {
    spdlog::info("source ended: {}; {} samples published, {} rejected", status.detail, accepted_,
                 rejected_);
  } else {
    spdlog::error("source gone: {}; {} samples published, {} rejected", status.detail, accepted_,
                  rejected_);
  }
  health_ = ImuHealth{};
  publish_status();
  publisher_.flush_status(std::chrono::milliseconds(500));
  return clean ? kExitOk : kExitSourceFailed;
}

}  // namespace cover::ugv
