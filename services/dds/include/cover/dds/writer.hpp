#pragma once

#include <chrono>
#include <memory>

#include "cover/dds/backend.hpp"

namespace cover::dds {

// Typed writer for one topic. Movable, not copyable. `write` never throws.
template <typename T>
class Writer {
 public:
  Writer() = default;
  explicit Writer(std::unique_ptr<WriterBackend> backend) : backend_(std::move(backend)) {}

  bool write(const T& sample) { return backend_ && backend_->write(&sample); }
  std::size_t matched_readers() const { return backend_ ? backend_->matched_readers() : 0; }

  // Reliable topics: waits until every matched reader acknowledged what was written
  // (call before destroying a writer whose last samples must arrive).
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) {
    return backend_ && backend_->wait_for_acknowledgments(timeout);
  }

  // Waits until at least `count` readers matched; false on timeout.
  bool wait_for_readers(std::size_t count, std::chrono::milliseconds timeout) const;

  explicit operator bool() const { return static_cast<bool>(backend_); }

 private:
  std::unique_ptr<WriterBackend> backend_;
};

// Polls a matched count until it reaches `count` or `timeout` passes (discovery events
// are not exposed uniformly by the two vendors, so a 1 ms poll is the simple, portable way).
bool wait_until_matched(const std::function<std::size_t()>& matched, std::size_t count,
                        std::chrono::milliseconds timeout);

template <typename T>
bool Writer<T>::wait_for_readers(std::size_t count, std::chrono::milliseconds timeout) const {
  return wait_until_matched([this] { return matched_readers(); }, count, timeout);
}

}  // namespace cover::dds
