#include "cover/launch/executable_lookup.hpp"

#include <unistd.h>

#include <filesystem>
#include <sstream>

namespace cover::launch {
namespace {

bool is_executable_file(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error) && access(path.c_str(), X_OK) == 0;
}

}  // namespace

std::optional<std::string> resolve_executable(const std::string& executable,
                                              const std::string& launch_dir,
                                              const std::string& self_dir,
                                              const std::string& search_path) {
  namespace fs = std::filesystem;
  if (executable.find('/') != std::string::npos) {
    const fs::path path = fs::path(launch_dir) / executable;  // an absolute path stays as is
    if (is_executable_file(path)) return path.lexically_normal().string();
    return std::nullopt;
  }
  if (!self_dir.empty() && is_executable_file(fs::path(self_dir) / executable)) {
    return (fs::path(self_dir) / executable).string();
  }
  std::istringstream folders(search_path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;  // an empty entry would mean the cwd: too surprising
    if (is_executable_file(fs::path(folder) / executable)) {
      return (fs::path(folder) / executable).string();
    }
  }
  return std::nullopt;
}

std::string self_executable_dir() {
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string() : self.parent_path().string();
}

}  // namespace cover::launch
