#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>

#include "cover/clock/clock.hpp"
#include "cover/dds/backend.hpp"
#include "cover/dds/writer.hpp"

namespace cover::dds {

// Typed reader for one topic, created by Participant::make_reader. It keeps the latest
// sample with its local receive time (monotonic), and optionally calls a callback on the
// vendor's receive thread for every sample.
template <typename T>
class Reader {
 public:
  using Callback = std::function<void(const T&)>;

  struct Received {
    T sample;
    std::int64_t received_monotonic_ns = 0;
  };

  // Shared between the reader and the vendor's receive thread.
  class State {
   public:
    // `deadline_s` > 0: the expected longest period between samples (QosProfile::deadline_s).
    explicit State(Callback callback, double deadline_s = 0.0)
        : callback_(std::move(callback)),
          deadline_ns_(static_cast<std::int64_t>(deadline_s * 1e9)) {}
    // The callback runs first: a thread woken by the count (wait_beyond) must find what the
    // callback did with the sample. Woken first, the UAV agent would step on the previous
    // relative state while its callback still files this one: a period of extra latency.
    void deliver(const T& sample) {
      if (callback_) callback_(sample);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const std::int64_t now_ns = cover::clock::monotonic_ns();
        closed_misses_ += periods_missed(now_ns);
        latest_ = Received{sample, now_ns};
        ++count_;
      }
      changed_.notify_all();
    }
    std::optional<Received> latest() const {
      std::lock_guard<std::mutex> lock(mutex_);
      return latest_;
    }
    std::uint64_t count() const {
      std::lock_guard<std::mutex> lock(mutex_);
      return count_;
    }
    // Deadline periods that passed without a sample since the first one: a gap of n whole
    // periods counts n, as the vendors' requested-deadline status does. Counted here, not by
    // the vendor: Fast DDS reschedules a deadline timer on every sample received and written,
    // a wake-up of its event thread each (see fastdds_backend.cpp).
    std::uint64_t deadline_misses() const {
      std::lock_guard<std::mutex> lock(mutex_);
      return closed_misses_ + periods_missed(cover::clock::monotonic_ns());
    }
    // Waits until more than `seen` samples arrived; false on timeout.
    bool wait_beyond(std::uint64_t seen, std::chrono::milliseconds timeout) {
      return wait_beyond_until(seen, std::chrono::steady_clock::now() + timeout);
    }
    bool wait_beyond_until(std::uint64_t seen, std::chrono::steady_clock::time_point deadline) {
      std::unique_lock<std::mutex> lock(mutex_);
      return changed_.wait_until(lock, deadline, [&] { return count_ > seen; });
    }

   private:
    std::uint64_t periods_missed(std::int64_t now_ns) const {  // mutex_ held
      if (deadline_ns_ <= 0 || !latest_) return 0;
      return static_cast<std::uint64_t>((now_ns - latest_->received_monotonic_ns) / deadline_ns_);
    }

    Callback callback_;
    std::int64_t deadline_ns_ = 0;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::optional<Received> latest_;
    std::uint64_t count_ = 0;
    std::uint64_t closed_misses_ = 0;  // of the gaps before the latest sample
  };

  Reader() = default;
  Reader(std::unique_ptr<ReaderBackend> backend, std::shared_ptr<State> state)
      : state_(std::move(state)), backend_(std::move(backend)) {}

  // The newest sample and when it arrived, if any arrived yet.
  std::optional<Received> latest() const { return state_ ? state_->latest() : std::nullopt; }
  std::uint64_t received_count() const { return state_ ? state_->count() : 0; }

  // Waits until a sample beyond the first `already_seen` arrives.
  bool wait_for_sample(std::chrono::milliseconds timeout, std::uint64_t already_seen = 0) {
    return state_ && state_->wait_beyond(already_seen, timeout);
  }
  // The same until a point in time (finer than a millisecond).
  bool wait_for_sample_until(std::chrono::steady_clock::time_point deadline,
                             std::uint64_t already_seen = 0) {
    return state_ && state_->wait_beyond_until(already_seen, deadline);
  }

  std::size_t matched_writers() const { return backend_ ? backend_->matched_writers() : 0; }
  // Deadline periods (the topic's QosProfile::deadline_s) that passed without a sample,
  // counted from the first sample; 0 for a topic without a deadline.
  std::uint64_t deadline_misses() const { return state_ ? state_->deadline_misses() : 0; }
  bool wait_for_writers(std::size_t count, std::chrono::milliseconds timeout) const {
    return wait_until_matched([this] { return matched_writers(); }, count, timeout);
  }

  explicit operator bool() const { return static_cast<bool>(backend_); }

 private:
  // Declared before the backend so the backend (and its receive thread) goes first.
  std::shared_ptr<State> state_;
  std::unique_ptr<ReaderBackend> backend_;
};

}  // namespace cover::dds
