#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "cover/dds/security_options.hpp"
#include "cover/dds/vendor.hpp"

namespace cover::dds {

// How a process joins the DDS network. Loaded from config/dds.yaml (see load_file), then
// overridden by --dds / $COVER_DDS and --domain / $COVER_DDS_DOMAIN; a profile of the
// file (--dds-profile / $COVER_DDS_PROFILE) replaces its network keys.
struct ParticipantOptions {
  Vendor vendor = Vendor::FastDds;
  int domain_id = 0;  // 0..232 (the RTPS port formula overflows above 232)
  // Network interface name to use ("lo" for one host; "wlan0" in the field). Empty: the
  // vendor's default choice. On "lo" Cyclone is told that multicast works, which makes
  // it discover Fast DDS participants in milliseconds instead of seconds.
  std::string interface_name = "lo";
  // Unicast discovery peers (IPv4 addresses), for networks that drop multicast (WiFi).
  // When set, multicast discovery is turned off on both vendors.
  std::vector<std::string> peers;
  // A Fast DDS Discovery Server, "IPv4:port" (`fastdds discovery -i 0 -l IPv4 -p port`,
  // started by cover-launch when the profile names one): Fast DDS participants discover
  // each other through it, as its clients, instead of every participant announcing itself
  // to every other (simple discovery: N^2 announcements). Empty: simple discovery. Cyclone
  // DDS participants cannot be its clients and keep `peers` (a Cyclone process then meets
  // Fast DDS processes only through the server's own announcements: keep one vendor).
  std::string discovery_server;
  // Fast DDS's shared-memory transport between Fast DDS processes on one host. Off by
  // default: a Fast DDS process that is killed leaves its segments in /dev/shm, and a
  // participant restarted on its port could not receive over it (a task manager killed
  // and restarted stayed deaf to its fleet); loopback UDP costs a few microseconds.
  bool fastdds_shared_memory = false;
  // How often a participant announces itself (SPDP), in seconds; 0: the vendor's default
  // (Fast DDS 3 s, Cyclone 30 s). On a lossy link a lost announcement delays discovery
  // by one period: a UAV agent that discovers a UGV's IMU writer late fails its stage.
  double announcement_period_s = 0.0;
  // Participants a unicast peer address may hold, so the ports each announcement goes to
  // per peer (Fast DDS's initial-peers range, Cyclone's highest participant index): 72 for a
  // fleet of 32 UAVs and 32 UGVs on one host, its simulator and services. Over WiFi each
  // peer is one vehicle with a few processes: every announcement costs peers x this many
  // datagrams, and 72 x 32 peers saturated a 10 Mbit link (docs/benchmarks.md, discovery
  // over the emulated WiFi).
  int participants_per_peer = 72;
  // Fast DDS's UDP receive buffer, bytes; 0: the OS default (212992 on Debian 12). A
  // process that must not lose a burst while it is descheduled (the flight recorder) asks
  // for more; Linux caps it at net.core.rmem_max. Cyclone sizes its own (>= 1 MiB).
  int receive_buffer_bytes = 0;
  std::string participant_name = "cover";
  // DDS-Security (authentication, access control, encryption); off by default.
  SecurityOptions security;

  void validate() const;  // throws DdsError naming the bad field
  // Reads `dds:` of `path`, then, when `profile` is not empty, the network keys of
  // `dds.profiles.<profile>` on top (e.g. "wifi"). Throws ConfigError, also for a
  // profile the file does not define.
  static ParticipantOptions load_file(const std::string& path, const std::string& profile = "");
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static ParticipantOptions from_yaml(const YAML::Node& document, const std::string& source,
                                      const std::string& profile = "");
};

inline constexpr int kMaxDomainId = 232;
// Cyclone's participant index and Fast DDS's participant id map to port pairs of one
// domain's range (250 ports, 2 per participant after the first 10): at most 120.
inline constexpr int kMaxParticipantsPerPeer = 120;

// The server id of the Discovery Server that `discovery_server` names: `fastdds discovery
// -i 0`, whose GUID prefix the clients must know (44.53.<id>.5f.45.50.52.4f.53.49.4d.41).
inline constexpr int kDiscoveryServerId = 0;

// "IPv4:port" split; throws DdsError naming `text` when it is not one.
struct ServerAddress {
  std::string address;
  int port = 0;
};
ServerAddress parse_server_address(const std::string& text);

// $COVER_DDS_PROFILE when set and not empty, else `fallback`.
std::string profile_from_environment(const std::string& fallback);

// Applies $COVER_DDS, $COVER_DDS_DOMAIN, $COVER_DDS_SECURITY (a fleet directory: turns
// security on) and $COVER_DDS_IDENTITY on top of `options`.
ParticipantOptions apply_environment(ParticipantOptions options);

}  // namespace cover::dds
