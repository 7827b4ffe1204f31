#pragma once

#include <optional>
#include <string>

#include "security_commands.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace cover::cli {

// `cover security init|check`: DDS-Security fleet directories (docs/security.md,
// security_commands.hpp).
class SecurityCli {
 public:
  explicit SecurityCli(CLI::App& app);
  bool chosen() const;
  int run();

 private:
  CLI::App* init_ = nullptr;
  CLI::App* check_ = nullptr;
  SecurityInitRequest init_request_;
  std::string check_directory_;
  bool check_json_ = false;
  std::optional<int> check_warning_days_;
};

}  // namespace cover::cli
