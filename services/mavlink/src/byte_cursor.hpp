#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace cover::mavlink::detail {

// Little-endian field access over a payload buffer, in wire order. The byte order is
// written out (not memcpy of the host's) so the codec is right on any host.
template <typename T>
struct Unsigned {
  using type = std::make_unsigned_t<T>;
};
template <>
struct Unsigned<float> {
  using type = std::uint32_t;
};
template <>
struct Unsigned<double> {
  using type = std::uint64_t;
};
template <>
struct Unsigned<char> {
  using type = std::uint8_t;
};

class PayloadWriter {
 public:
  explicit PayloadWriter(std::uint8_t* payload) : at_(payload) {}

  template <typename T>
  void put(T value) {
    using U = typename Unsigned<T>::type;
    U bits = 0;
    std::memcpy(&bits, &value, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      *at_++ = static_cast<std::uint8_t>(bits >> (8 * i));
    }
  }
  template <typename T, std::size_t N>
  void put(const std::array<T, N>& values) {
    for (const T& value : values) put(value);
  }

 private:
  std::uint8_t* at_;
};

class PayloadReader {
 public:
  explicit PayloadReader(const std::uint8_t* payload) : at_(payload) {}

  template <typename T>
  void get(T& value) {
    using U = typename Unsigned<T>::type;
    U bits = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      bits = static_cast<U>(bits | (static_cast<U>(*at_++) << (8 * i)));
    }
    std::memcpy(&value, &bits, sizeof(T));
  }
  template <typename T, std::size_t N>
  void get(std::array<T, N>& values) {
    for (T& value : values) get(value);
  }

 private:
  const std::uint8_t* at_;
};

}  // namespace cover::mavlink::detail
