#pragma once

#include <cstdint>

namespace cover::sim {

// Derives independent, reproducible seeds for each random stream (sensor, UGV) from the
// world seed (SplitMix64 finaliser), so adding one noise source never shifts another.
inline std::uint64_t derive_seed(std::uint64_t world_seed, std::uint64_t stream) {
  std::uint64_t z = world_seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace cover::sim
