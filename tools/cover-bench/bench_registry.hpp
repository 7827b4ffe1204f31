#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace cover::bench {

// A subcommand of cover-bench: receives the arguments after its name, returns the exit
// code. Each prints JSON on stdout with --json, a readable summary otherwise.
using BenchMain = std::function<int(const std::vector<std::string>& args)>;

struct BenchEntry {
  std::string summary;
  BenchMain run;
  // It ends on SIGINT / SIGTERM by itself (ShutdownSignal), cleaning up what it set up;
  // otherwise cover-bench stops its child processes and exits 130
  // (process::stop_children_on_shutdown).
  bool handles_shutdown = false;
};

std::map<std::string, BenchEntry>& registry();

// Static registration: `static const cover::bench::Registrar r{"planner", "...", &fn};`
struct Registrar {
  Registrar(const std::string& name, const std::string& summary, BenchMain run,
            bool handles_shutdown = false) {
    registry()[name] = BenchEntry{summary, std::move(run), handles_shutdown};
  }
};

}  // namespace cover::bench
