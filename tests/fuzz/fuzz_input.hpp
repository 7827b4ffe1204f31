#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <string>

namespace cover::fuzz {

// The contract a target checks, beyond "no crash": a violation aborts with the reason, so
// libFuzzer (and the replay runner) report it as a crash with the input saved.
[[noreturn]] inline void violated(const std::string& what) {
  std::cerr << "fuzz contract violated: " << what << std::endl;
  std::abort();
}

inline void require(bool condition, const std::string& what) {
  if (!condition) violated(what);
}

// Reads typed values from the fuzzer's bytes; past the end every read is zero. Doubles
// come out as the hostile values a sensor or a foreign writer can send (NaN, infinities,
// huge, tiny, negative zero) far more often than raw bit patterns would give them.
class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool empty() const { return pos_ >= size_; }
  std::size_t left() const { return empty() ? 0 : size_ - pos_; }

  std::uint8_t byte() { return empty() ? 0 : data_[pos_++]; }

  template <typename T>
  T raw() {
    T value{};
    const std::size_t n = std::min(sizeof(T), left());
    if (n > 0) std::memcpy(&value, data_ + pos_, n);
    pos_ += n;
    return value;
  }

  // An integer in [lo, hi].
  long long range(long long lo, long long hi) {
    const auto span = static_cast<unsigned long long>(hi - lo) + 1ULL;
    const auto r = raw<std::uint32_t>();
    return span == 0 ? lo + static_cast<long long>(r) : lo + static_cast<long long>(r % span);
  }

  double real() {
    switch (byte() % 12) {
      case 0:
        return std::numeric_limits<double>::quiet_NaN();
      case 1:
        return std::numeric_limits<double>::infinity();
      case 2:
        return -std::numeric_limits<double>::infinity();
      case 3:
        return std::numeric_limits<double>::max();
      case 4:
        return std::numeric_limits<double>::denorm_min();
      case 5:
        return -0.0;
      case 6:
        return raw<double>();  // any bit pattern
      default:                 // a plausible value: what a real sensor gives
        return static_cast<double>(raw<std::int16_t>()) / 256.0;
    }
  }

  std::string text(std::size_t max_length) {
    const std::size_t wanted = byte() % (max_length + 1);  // before left(): it consumes
    const std::size_t n = std::min(wanted, left());
    std::string s(reinterpret_cast<const char*>(data_ + pos_), n);
    pos_ += n;
    return s;
  }

  std::string rest() {
    std::string s(reinterpret_cast<const char*>(data_ + pos_), left());
    pos_ = size_;
    return s;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace cover::fuzz
