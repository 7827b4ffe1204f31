#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "cover/sampc/sampc_params.hpp"

namespace cover::bench {

// Parses a subcommand's arguments with CLI11. Returns -1 to go on, or the exit code the
// subcommand should return (0 after --help, 2 after a usage error, whatever CLI11's own code:
// not_measured.hpp lists the subcommands' codes). CLI11 consumes a vector from its back,
// hence the reverse.
inline int parse_args(CLI::App& app, std::vector<std::string> args) {
  std::reverse(args.begin(), args.end());
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return -1;
}

// SAMPC's method names in cover::sampc::kModes' order: for CLI::IsMember and help texts.
inline std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const sampc::Mode mode : sampc::kModes) names.emplace_back(sampc::to_string(mode));
  return names;
}

// "cover | no-ref-vxy | coni-mpc" with `separator` between the names.
inline std::string joined_method_names(const std::string& separator) {
  std::string text;
  for (const std::string& name : method_names()) text += (text.empty() ? "" : separator) + name;
  return text;
}

// The comparison tables (Table 1, Fig. 8) run and list the CoNi-MPC baseline first and
// COVER last, as the paper's tables do (kModes reversed), then the methods beyond the paper
// (intercept).
inline std::vector<sampc::Mode> baseline_first_modes() {
  std::vector<sampc::Mode> modes{std::rbegin(sampc::kModes), std::rend(sampc::kModes)};
  const auto beyond_paper = [](sampc::Mode mode) { return mode == sampc::Mode::Intercept; };
  std::stable_partition(modes.begin(), modes.end(),
                        [&](sampc::Mode mode) { return !beyond_paper(mode); });
  return modes;
}

}  // namespace cover::bench
