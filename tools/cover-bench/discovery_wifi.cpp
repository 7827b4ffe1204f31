#include "discovery_wifi.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace cover::bench {

namespace {

// A run tag of scripts/wifi-sim: this process's, 1-6 of [a-z0-9].
std::string run_tag() {
  char tag[8];
  std::snprintf(tag, sizeof tag, "%x", static_cast<unsigned>(getpid()) & 0xffffffu);
  return tag;
}

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "" : " ") + word;
  return text;
}

std::string log_path(const std::string& tag, const std::string& what) {
  return (std::filesystem::temp_directory_path() /
          ("cover_discovery_wifi_" + tag + "_" + what + ".log"))
      .string();
}

}  // namespace

const char* wifi_sim_script() {
#ifdef COVER_WIFI_SIM
  return COVER_WIFI_SIM;
#else
  return "scripts/wifi-sim";
#endif
}

DiscoveryWifi::DiscoveryWifi(const WifiLink& link, int processes) : tag_(run_tag()) {
  for (int k = 0; k < processes; ++k) nodes_.push_back(process_node(k));
  nodes_.push_back(kServerNode);
  const std::string nodes = joined(nodes_);
  setup_ = std::make_unique<process::ScopedSetup>(
      std::vector<std::string>{wifi_sim_script(), "--run", tag_, "up", "--loss-percent",
                               std::to_string(link.loss_percent), "--rate", link.rate,
                               "--multicast", link.multicast ? "pass" : "drop", "--nodes", nodes},
      std::vector<std::string>{wifi_sim_script(), "--run", tag_, "down"}, log_path(tag_, "net"));
  if (!setup_->ok()) return;
  // The addresses as the script gives them ("NODE ADDRESS" lines, in node order).
  const std::string addresses_log = log_path(tag_, "addresses");
  const auto listed = process::run_command({wifi_sim_script(), "addresses", "--nodes", nodes},
                                           addresses_log, std::chrono::seconds(10));
  std::error_code ignored;
  if (listed.exit_code == 0) std::filesystem::remove(addresses_log, ignored);
  std::istringstream lines(listed.output);
  std::string node, address;
  while (lines >> node >> address) {
    if (addresses_.size() < nodes_.size() && node == nodes_[addresses_.size()]) {
      addresses_.push_back(address);
    }
  }
}

std::vector<std::string> DiscoveryWifi::in_node(const std::string& node,
                                                const std::vector<std::string>& argv) const {
  // scripts/wifi-sim's namespace names: cwifi<TAG>-<NODE>.
  std::vector<std::string> wrapped{"/usr/bin/env", "ip", "netns", "exec",
                                   "cwifi" + tag_ + "-" + node};
  wrapped.insert(wrapped.end(), argv.begin(), argv.end());
  return wrapped;
}

std::string DiscoveryWifi::address(const std::string& node) const {
  for (std::size_t k = 0; k < nodes_.size() && k < addresses_.size(); ++k) {
    if (nodes_[k] == node) return addresses_[k];
  }
  throw std::invalid_argument("cover-bench discovery: no WiFi node '" + node + "'");
}

}  // namespace cover::bench
