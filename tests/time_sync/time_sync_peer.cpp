// A process in the clock exchange: time_sync_peer VENDOR DOMAIN PROCESS [--wait | PEER...].
// It answers the clock requests that name PROCESS; given peers, it also asks them (0.05 s
// bursts, then every 0.2 s), and with --wait it asks no one but holds its reply topic.
// Prints "ready" once it answers; on SIGTERM, when it asks, one line
// "delivered D foreign F peers P": the replies DDS delivered to it, those of them for
// another asker, and the peers it has an estimate of.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/time_sync/clock_responder.hpp"
#include "cover/time_sync/offset_monitor.hpp"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: time_sync_peer fastdds|cyclone DOMAIN PROCESS [--wait | PEER...]\n");
    return 2;
  }
  cover::process::ShutdownSignal::install();
  cover::dds::ParticipantOptions options;
  options.vendor = cover::dds::parse_vendor(argv[1]);
  options.domain_id = std::atoi(argv[2]);
  options.participant_name = argv[3];
  cover::dds::Participant participant(options);
  cover::time_sync::ClockResponder responder(participant, argv[3]);
  std::unique_ptr<cover::time_sync::OffsetMonitor> monitor;
  if (argc > 4) {
    cover::time_sync::MonitorOptions asking;
    asking.process = argv[3];
    const std::string first = argv[4];
    asking.wait_for_peers = first == "--wait";
    if (!asking.wait_for_peers) asking.peers.assign(argv + 4, argv + argc);
    asking.params.burst_count = 16;
    asking.params.burst_period_s = 0.05;
    asking.params.request_period_s = 0.2;
    monitor = std::make_unique<cover::time_sync::OffsetMonitor>(participant, asking);
  }
  std::printf("ready\n");
  std::fflush(stdout);
  while (!cover::process::ShutdownSignal::wait_for(std::chrono::milliseconds(200))) {
  }
  if (monitor) {
    std::printf("delivered %llu foreign %llu peers %zu\n",
                static_cast<unsigned long long>(monitor->replies_delivered()),
                static_cast<unsigned long long>(monitor->foreign_replies()),
                monitor->offsets().size());
    std::fflush(stdout);
  }
  std::fprintf(stderr, "answered %llu, refused %llu\n",
               static_cast<unsigned long long>(responder.answered()),
               static_cast<unsigned long long>(responder.refused()));
  return 0;
}
