#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <utility>

namespace cover::wire::detail {

// Each mapping is one table of (library, wire) pairs, read in both directions.
template <typename Lib, typename Wire, std::size_t N>
Wire lib_to_wire(const std::array<std::pair<Lib, Wire>, N>& table, Lib value, Wire fallback) {
  for (const auto& [lib, wire] : table) {
    if (lib == value) return wire;
  }
  return fallback;
}

template <typename Lib, typename Wire, std::size_t N>
std::optional<Lib> wire_to_lib(const std::array<std::pair<Lib, Wire>, N>& table, Wire value) {
  for (const auto& [lib, wire] : table) {
    if (wire == value) return lib;
  }
  return std::nullopt;
}

}  // namespace cover::wire::detail
