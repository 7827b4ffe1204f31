#include "cover_binary.hpp"

#include <cstdlib>

#include "cover/launch/executable_lookup.hpp"

namespace cover::bench {

std::string cover_binary(const std::string& name) {
#ifdef COVER_BUILD_BIN_DIRS
  std::string search = COVER_BUILD_BIN_DIRS;
#else
  std::string search;
#endif
  search += ":" + launch::self_executable_dir();
  const char* path = std::getenv("PATH");
  if (path != nullptr) search += std::string(":") + path;
  return launch::resolve_executable(name, "", "", search).value_or(name);
}

}  // namespace cover::bench
