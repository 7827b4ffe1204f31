#include "cover/shm/segment_name.hpp"

#include <stdexcept>

namespace cover::shm {
namespace {

// Same bound as the DDS layer: the RTPS port formula overflows above domain 232.
constexpr int kMaxDomainId = 232;
constexpr std::size_t kMaxRunIdLength = 40;

bool is_run_id_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

void check_run_id(const std::string& run_id) {
  if (run_id.empty() || run_id.size() > kMaxRunIdLength) {
    throw std::invalid_argument("shared-memory run id '" + run_id + "' must have 1 to " +
                                std::to_string(kMaxRunIdLength) + " characters, it has " +
                                std::to_string(run_id.size()));
  }
  for (const char c : run_id) {
    if (!is_run_id_char(c)) {
      throw std::invalid_argument("shared-memory run id '" + run_id +
                                  "' may contain only letters, digits and '_'");
    }
  }
}

}  // namespace

std::string segment_name(int dds_domain, const std::string& run_id) {
  if (dds_domain < 0 || dds_domain > kMaxDomainId) {
    throw std::invalid_argument("shared-memory segment: DDS domain " + std::to_string(dds_domain) +
                                " is outside 0.." + std::to_string(kMaxDomainId));
  }
  check_run_id(run_id);
  return "/cover_sim_d" + std::to_string(dds_domain) + "_" + run_id;
}

std::string segment_path(const std::string& name) {
  const bool has_slash = !name.empty() && name.front() == '/';
  return "/dev/shm/" + (has_slash ? name.substr(1) : name);
}

}  // namespace cover::shm
