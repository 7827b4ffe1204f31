#include "concurrent_floor.hpp"

#include <iostream>

#include "bench_stats.hpp"

namespace cover::bench {
namespace {
constexpr int kWarmUpTrips = 50;
// Round trips per batch: how late stop() may take effect, in periods.
constexpr int kTripsPerBatch = 10;
}  // namespace

ConcurrentFloor::ConcurrentFloor(const PingPongOptions& options, double rate_hz)
    : rate_hz_(rate_hz), thread_([this, options] { ping(options); }) {
  std::unique_lock<std::mutex> lock(mutex_);
  started_cv_.wait(lock, [this] { return started_; });
}

ConcurrentFloor::~ConcurrentFloor() {
  stop_pinging();
}

void ConcurrentFloor::stop_pinging() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_requested_ = true;
  }
  if (thread_.joinable()) thread_.join();
}

bool ConcurrentFloor::failed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return !error_.empty();
}

void ConcurrentFloor::ping(PingPongOptions options) {
  try {
    PingPong ping_pong(options);
    ping_pong.run(kWarmUpTrips, rate_hz_);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ping_priority_ = ping_pong.ping_realtime_priority();
      pong_priority_ = ping_pong.pong_realtime_priority();
      pong_cpus_ = ping_pong.pong_cpus();
      started_ = true;
    }
    started_cv_.notify_all();
    for (;;) {
      const RoundTrips batch = ping_pong.run(kTripsPerBatch, rate_hz_);
      std::lock_guard<std::mutex> lock(mutex_);
      trips_.sent += batch.sent;
      trips_.received += batch.received;
      trips_.round_trip_us.insert(trips_.round_trip_us.end(), batch.round_trip_us.begin(),
                                  batch.round_trip_us.end());
      if (stop_requested_) return;
    }
  } catch (const std::exception& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = e.what();
      started_ = true;
    }
    started_cv_.notify_all();
  }
}

nlohmann::json ConcurrentFloor::stop() {
  stop_pinging();
  std::lock_guard<std::mutex> lock(mutex_);
  if (!error_.empty() || trips_.round_trip_us.empty()) {
    std::cerr << "cover-bench: a floor was not measured: "
              << (error_.empty() ? "no round trip came back" : error_) << "\n";
    return nullptr;
  }
  return {{"p50_ms", percentile(trips_.round_trip_us, 0.50) / 1000.0},
          {"p99_ms", percentile(trips_.round_trip_us, 0.99) / 1000.0},
          {"samples", trips_.received},
          {"lost", trips_.sent - trips_.received},
          {"ping_realtime_priority", ping_priority_},
          {"pong_realtime_priority", pong_priority_},
          {"pong_cpus", pong_cpus_}};
}

}  // namespace cover::bench
