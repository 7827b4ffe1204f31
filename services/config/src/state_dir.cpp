#include "cover/config/state_dir.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "cover/config/config_error.hpp"

namespace cover::config {
namespace {

// The variable's value when it is an absolute path, else "".
std::string absolute_path_from(const char* variable) {
  const char* value = std::getenv(variable);
  if (!value || value[0] != '/') return "";
  return value;
}

}  // namespace

std::string default_state_dir() {
  const std::string xdg_state = absolute_path_from("XDG_STATE_HOME");
  if (!xdg_state.empty()) return (std::filesystem::path(xdg_state) / "cover").string();
  const std::string home = absolute_path_from("HOME");
  if (!home.empty()) return (std::filesystem::path(home) / ".local/state/cover").string();
  throw ConfigError(
      "no state directory: neither XDG_STATE_HOME nor HOME is an absolute path (set one, or "
      "name the file yourself)");
}

void create_state_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_directory(dir, error)) return;
  if (!fs::create_directories(dir, error) && error) {
    throw ConfigError("cannot create state directory " + dir + ": " + error.message());
  }
  fs::permissions(dir, fs::perms::owner_all, fs::perm_options::replace, error);
}

}  // namespace cover::config
