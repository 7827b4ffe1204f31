#pragma once

#include <cstdint>
#include <string>

#include "cover/dds/cli_options.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace cover::cli {

// Exit codes of `cover fc ...`.
inline constexpr int kFcAccepted = 0;  // status: a bridge reported; command: accepted;
                                       // check: every parameter as COVER needs it
inline constexpr int kFcRefused = 1;   // the autopilot (or its bridge) said no: reason printed;
                                       // check: a parameter is wrong (named)
inline constexpr int kFcNoAnswer = 3;  // no bridge, or the autopilot never answered

// `cover fc status|check|arm|disarm|offboard|land U`: an operator's view of, and commands
// to, one UAV's autopilot through its cover-fc-bridge. Each command waits for the
// autopilot's answer (COMMAND_ACK, relayed by the bridge); `check` waits until the bridge
// has read every parameter COVER depends on and judges them.
class FcCommands {
 public:
  explicit FcCommands(CLI::App& app);
  bool chosen() const;
  int run();

 private:
  int status();
  int check();
  int command();

  CLI::App* fc_ = nullptr;
  std::string action_;
  std::uint32_t uav_id_ = 0;
  double timeout_s_ = 5.0;
  bool json_ = false;
  dds::DdsCliOptions dds_;
};

}  // namespace cover::cli
