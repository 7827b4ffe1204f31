#include "bench_registry.hpp"

namespace cover::bench {

std::map<std::string, BenchEntry>& registry() {
  static std::map<std::string, BenchEntry> entries;
  return entries;
}

}  // namespace cover::bench
