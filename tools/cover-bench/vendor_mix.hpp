#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace cover::bench {

// Which DDS vendor each kind of process runs on. The one table of the benchmarks that run
// the system as processes (e2e, faults, wifi).
struct VendorMix {
  const char* name;
  const char* sim;
  const char* ugv;  // the UGV agents
  const char* uav;  // the UAV agent
};

// fastdds / cyclone: every process on one vendor; mixed: the simulator and the UGV agents
// on Cyclone, the UAV agent on Fast DDS, so relative states, IMU and commands all cross
// vendors.
inline const std::vector<VendorMix>& vendor_mixes() {
  static const std::vector<VendorMix> mixes = {
      {"fastdds", "fastdds", "fastdds", "fastdds"},
      {"cyclone", "cyclone", "cyclone", "cyclone"},
      {"mixed", "cyclone", "cyclone", "fastdds"},
  };
  return mixes;
}

inline std::vector<std::string> vendor_mix_names() {
  std::vector<std::string> names;
  for (const VendorMix& mix : vendor_mixes()) names.emplace_back(mix.name);
  return names;
}

// Throws std::invalid_argument naming the valid mixes.
inline const VendorMix& vendor_mix(const std::string& name) {
  for (const VendorMix& mix : vendor_mixes()) {
    if (name == mix.name) return mix;
  }
  throw std::invalid_argument("unknown DDS vendor mix '" + name +
                              "' (valid: fastdds, cyclone, mixed)");
}

// cover-launch's --dds flags for a launch file whose processes are named sim, ugv*, uav*.
inline std::vector<std::string> launch_dds_flags(const VendorMix& mix) {
  return {"--dds", std::string("*=") + mix.sim,   "--dds", std::string("ugv*=") + mix.ugv,
          "--dds", std::string("uav*=") + mix.uav};
}

}  // namespace cover::bench
