#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace cover::bench {

// Parses a subcommand's arguments with CLI11. Returns -1 to go on, or the exit code the
// subcommand should return (0 after --help, non-zero after a usage error).
// CLI11 consumes a vector from its back, hence the reverse.
inline int parse_args(CLI::App& app, std::vector<std::string> args) {
  std::reverse(args.begin(), args.end());
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return -1;
}

}  // namespace cover::bench
