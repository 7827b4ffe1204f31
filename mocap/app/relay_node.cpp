#include "relay_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/wire/sensors.hpp"

namespace cover::mocap {
namespace {

constexpr std::int64_t kStatsPeriodNs = 10'000'000'000;
// The messages of one repeated frame arrive together; the next repetition 20 ms later.
constexpr std::int64_t kRepeatSpacingNs = 5'000'000;

}  // namespace

RelayNode::RelayNode(dds::Participant& participant, const RelayParams& params,
                     vrpn::ClientOptions client)
    : params_(params),
      client_(std::move(client)),
      assembler_(params.bodies.size(), static_cast<std::int64_t>(params.frame_timeout_s * 1e9)),
      estimator_(params),
      server_clock_(params.time_source, params.offset_window_s) {
  for (const auto& [uav, ugv] : estimator_.pair_ids()) {
    writers_.push_back(participant.make_writer(dds::topics::relative_state(
        static_cast<std::uint32_t>(uav), static_cast<std::uint32_t>(ugv))));
  }
  outputs_.reserve(writers_.size());
}

void RelayNode::on_report(const vrpn::TrackerReport& report) {
  if (report.kind == vrpn::TrackerReport::Kind::Velocity) {
    ++velocity_reports_;  // the filter's velocity is used: one method whatever the server
    return;
  }
  BodySample sample;
  sample.reported = true;
  sample.valid = report.valid;
  if (report.valid) {
    sample.pose = to_world(report.position, report.quaternion_xyzw, params_.up_axis, params_.units);
  }
  const std::int64_t arrival_ns = clock::system_ns();
  const bool complete = assembler_.add(report.body, report.time.to_ns(), arrival_ns, sample);
  if (assembler_.repeat()) {
    // The newest frame again (a lockstep simulator republishing its tick, every 20 ms):
    // its states again, once per repetition, in case they were lost on their way.
    const std::int64_t now_ns = clock::monotonic_ns();
    if (now_ns - republished_mono_ns_ >= kRepeatSpacingNs) {
      republished_mono_ns_ = now_ns;
      ++republished_frames_;
      write_outputs();
    }
    return;
  }
  if (complete) {
    publish(assembler_.frame(), clock::monotonic_ns());
    if (assembler_.poll(arrival_ns)) publish(assembler_.frame(), clock::monotonic_ns());
  }
}

void RelayNode::publish(const Frame& frame, std::int64_t completed_mono_ns) {
  const std::int64_t stamp_ns = server_clock_.to_ours(frame.server_ns, frame.first_arrival_ns);
  estimator_.on_frame(frame, stamp_ns, outputs_);
  write_outputs();
  latency_ns_[latency_count_++ % latency_ns_.size()] = clock::monotonic_ns() - completed_mono_ns;
  ++published_frames_;
}

void RelayNode::write_outputs() {
  for (std::size_t i = 0; i < outputs_.size() && i < writers_.size(); ++i) {
    const RelativeOutput& o = outputs_[i];
    msg::RelativeState m = wire::to_msg(o.state, static_cast<std::uint32_t>(o.uav),
                                        static_cast<std::uint32_t>(o.ugv), o.position_std_m);
    m.stamp_ns = o.stamp_ns;
    m.valid = o.valid;
    writers_[i].write(m);
  }
}

void RelayNode::log_stats() {
  const auto s = client_.stats();
  const std::size_t n = std::min<std::size_t>(latency_count_, latency_ns_.size());
  std::vector<std::int64_t> sorted(latency_ns_.begin(), latency_ns_.begin() + n);
  std::sort(sorted.begin(), sorted.end());
  auto pct = [&](double q) {
    return sorted.empty() ? 0.0 : sorted[static_cast<std::size_t>(q * (sorted.size() - 1))] * 1e-6;
  };
  spdlog::info(
      "frames {} published ({} again on request), relay latency p50 {:.3f} ms p99 {:.3f} ms "
      "(last {}), offset {:.3f} ms, {} jumps, {} restarts, {} invalid outputs, {} late samples; "
      "VRPN: {} connections, {} poses, {} lost samples, {} refused messages, {} bad lengths, {} "
      "velocity reports (unused: the filter's velocity is)",
      published_frames_, republished_frames_, pct(0.5), pct(0.99), n,
      server_clock_.offset_ns() * 1e-6, estimator_.stats().jumps, estimator_.stats().restarts,
      estimator_.stats().invalid_outputs, assembler_.late_samples(), s.connections, s.session.poses,
      s.session.lost_samples, s.session.refused(), s.session.bad_lengths, velocity_reports_);
}

void RelayNode::run() {
  const vrpn::ReportHandler handler = [this](const vrpn::TrackerReport& r) { on_report(r); };
  next_stats_mono_ns_ = clock::monotonic_ns() + kStatsPeriodNs;
  while (!process::ShutdownSignal::requested()) {
    client_.poll(std::chrono::milliseconds(1), handler);
    if (assembler_.poll(clock::system_ns())) publish(assembler_.frame(), clock::monotonic_ns());
    if (clock::monotonic_ns() >= next_stats_mono_ns_) {
      log_stats();
      next_stats_mono_ns_ += kStatsPeriodNs;
    }
  }
  log_stats();
}

}  // namespace cover::mocap
