// cover-bench: the project's benchmarks, each a subcommand printing medians (JSON with --json).
#include <chrono>
#include <iostream>

#include "bench_registry.hpp"
#include "cover/process/stop_children_on_shutdown.hpp"
#include "cover/startup/startup.hpp"

namespace {
void print_usage() {
  std::cerr << "usage: cover-bench <subcommand> [--json] [options]\n\nsubcommands:\n";
  for (const auto& [name, entry] : cover::bench::registry()) {
    std::cerr << "  " << name << std::string(name.size() < 12 ? 12 - name.size() : 1, ' ')
              << entry.summary << "\n";
  }
  std::cerr << "\n'cover-bench <subcommand> --help' for its options.\n"
            << "Exit codes: 0 measured; 1 a run failed (the reason on stderr); 2 usage or "
               "configuration error;\n4 measured nothing it was asked for (what, on stderr); "
               "130 stopped by SIGINT / SIGTERM.\n";
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    print_usage();
    return argc < 2 ? 2 : 0;
  }
  const auto& entries = cover::bench::registry();
  const auto found = entries.find(argv[1]);
  if (found == entries.end()) {
    std::cerr << "cover-bench: unknown subcommand '" << argv[1] << "'\n";
    print_usage();
    return 2;
  }
  // SIGINT / SIGTERM: the processes a benchmark started stop as a signal asks them (a
  // launch removes its shared memory), then cover-bench ends: 130, interrupted.
  constexpr std::chrono::seconds kChildrenGrace{10};
  constexpr int kExitInterrupted = 130;
  if (!found->second.handles_shutdown) {
    cover::process::stop_children_on_shutdown(kChildrenGrace, kExitInterrupted);
  }
  std::vector<std::string> args(argv + 2, argv + argc);
  // A benchmark that throws did not run (1); its own flags parse inside it (2 when bad).
  return cover::startup::run_guarded("cover-bench " + found->first, {},
                                     cover::startup::kExitFailure,
                                     [&] { return found->second.run(args); });
}
