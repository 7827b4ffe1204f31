#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "fault_row.hpp"
#include "vendor_mix.hpp"

namespace cover::bench {

// Scenario 2 in realtime over scripts/wifi-sim's field-like network (one network namespace
// per process, UDP loss on every link, a bandwidth cap, no multicast, DDS discovery by the
// unicast peers of the `wifi` profile): rows of fault `wifi_loss`. Needs root.
struct WifiOptions {
  int seeds = 10;  // per vendor mix, seeds 1..seeds
  int loss_percent = 10;
  std::string rate = "10mbit";
  int first_domain = 150;  // one per run, cycling over domain_count (150-159: no test uses them)
  int domain_count = 10;
};

struct WifiRun {
  FaultRow row;
  bool reported = false;        // the launch gave a result (false: nothing was measured)
  double latency_p99_ms = NAN;  // sensor-to-command, as cover-sim measured it; NaN: none
};

struct WifiResult {
  bool network_up = false;
  std::string network_output;  // scripts/wifi-sim's output when it could not set up
  std::vector<WifiRun> runs;
};

// Sets the network up, flies every mix in `mixes` for each seed, tears it down (also when
// a run throws). `on_run` sees each run as it ends (progress output).
WifiResult run_wifi(const WifiOptions& options, const std::vector<VendorMix>& mixes,
                    const std::function<void(const WifiRun&)>& on_run = {});

}  // namespace cover::bench
