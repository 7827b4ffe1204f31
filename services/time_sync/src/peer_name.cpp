#include "cover/time_sync/peer_name.hpp"

#include <unistd.h>

namespace cover::time_sync {

std::string peer_name(const std::string& process) {
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0 || host[0] == '\0') return "unknown-host/" + process;
  return std::string(host) + "/" + process;
}

bool peer_matches(std::string_view peer, const std::vector<std::string>& patterns) {
  if (patterns.empty()) return true;
  const std::size_t slash = peer.rfind('/');
  const std::string_view process = slash == std::string_view::npos ? peer : peer.substr(slash + 1);
  for (const std::string& pattern : patterns) {
    if (!pattern.empty() && pattern.back() == '*') {
      const std::string_view prefix(pattern.data(), pattern.size() - 1);
      if (process.substr(0, prefix.size()) == prefix) return true;
    } else if (process == pattern) {
      return true;
    }
  }
  return false;
}

}  // namespace cover::time_sync
