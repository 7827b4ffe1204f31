#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cover/process/scoped_setup.hpp"

namespace cover::bench {

// The link scripts/wifi-sim emulates (its `up` flags).
struct WifiLink {
  int loss_percent = 10;        // UDP datagrams dropped on every receiving link
  std::string rate = "10mbit";  // tbf cap on what each namespace sends
  bool multicast = false;       // the bridge passes multicast (false: drops it, as many APs do)
};

// `cover-bench discovery --wifi`'s network: one namespace of scripts/wifi-sim per
// discovery process (nodes p0, p1, ...) and one for the Fast DDS Discovery Server (node gs,
// the ground station's), under this process's own run tag, so that it never touches
// another run's namespaces. Up when made, down (namespaces, veths, bridge, nftables
// tables) when destroyed, also when a measurement throws.
class DiscoveryWifi {
 public:
  static constexpr const char* kServerNode = "gs";
  // The interface inside every namespace (the address DDS binds to).
  static constexpr const char* kInterface = "wifi0";

  DiscoveryWifi(const WifiLink& link, int processes);
  DiscoveryWifi(const DiscoveryWifi&) = delete;
  DiscoveryWifi& operator=(const DiscoveryWifi&) = delete;

  // Whether `wifi-sim up` succeeded; its output when it did not.
  bool ok() const { return setup_->ok() && addresses_.size() == nodes_.size(); }
  std::string output() const { return setup_->up_result().output; }

  static std::string process_node(int index) { return "p" + std::to_string(index); }
  // `argv` run inside `node`'s namespace (ip netns exec: the pid stays the program's).
  std::vector<std::string> in_node(const std::string& node,
                                   const std::vector<std::string>& argv) const;
  // The node's IPv4 address on the emulated WiFi.
  std::string address(const std::string& node) const;

 private:
  std::string tag_;
  std::vector<std::string> nodes_;
  std::vector<std::string> addresses_;  // in nodes_' order
  std::unique_ptr<process::ScopedSetup> setup_;
};

// scripts/wifi-sim (the source tree's, as the integration tests use it).
const char* wifi_sim_script();

}  // namespace cover::bench
