// A process that only answers clock requests: time_sync_peer VENDOR DOMAIN PROCESS.
// Prints "ready" once it answers; stops on SIGTERM. Its clock is the host's, shifted by
// COVER_TEST_CLOCK_OFFSET_MS when the test sets it.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/process/shutdown_signal.hpp"
#include "cover/time_sync/clock_responder.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: time_sync_peer fastdds|cyclone DOMAIN PROCESS\n");
    return 2;
  }
  cover::process::ShutdownSignal::install();
  cover::dds::ParticipantOptions options;
  options.vendor = cover::dds::parse_vendor(argv[1]);
  options.domain_id = std::atoi(argv[2]);
  options.participant_name = argv[3];
  cover::dds::Participant participant(options);
  cover::time_sync::ClockResponder responder(participant, argv[3]);
  std::printf("ready\n");
  std::fflush(stdout);
  while (!cover::process::ShutdownSignal::wait_for(std::chrono::milliseconds(200))) {
  }
  std::fprintf(stderr, "answered %llu, refused %llu\n",
               static_cast<unsigned long long>(responder.answered()),
               static_cast<unsigned long long>(responder.refused()));
  return 0;
}
