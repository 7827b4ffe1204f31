// The writer process of the cross-process tests: creates the segment named by argv[1]
// with layout version argv[2], prints "ready", then publishes counter 1, 2, ... (every
// element of the payload, and the stamp, equal to it) every 20 us or so until SIGTERM.
#include <cstdio>
#include <exception>
#include <string>

#include "cover/process/shutdown_signal.hpp"
#include "cover/shm/seqlock_writer.hpp"
#include "shm_test_payload.hpp"

int main(int argc, char** argv) {
  cover::process::ShutdownSignal::install();
  if (argc != 3) {
    std::fprintf(stderr, "usage: shm_test_writer NAME LAYOUT_VERSION\n");
    return 2;
  }
  try {
    using cover::shm::test::CounterPayload;
    cover::shm::SeqlockWriter<CounterPayload> writer(argv[1], std::stoul(argv[2]));
    std::printf("ready\n");
    std::fflush(stdout);
    for (std::uint64_t counter = 1;; ++counter) {
      writer.update([counter](CounterPayload& p) { cover::shm::test::fill(p, counter); },
                    static_cast<std::int64_t>(counter));
      cover::shm::test::work_between_writes();
      // ShutdownSignal::requested() takes a mutex: look only now and then.
      if (counter % 16 == 0 && cover::process::ShutdownSignal::requested()) return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shm_test_writer: %s\n", e.what());
    return 1;
  }
}
