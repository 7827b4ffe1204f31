#pragma once

#include <stdexcept>
#include <string>

namespace cover::dds {

// Raised when a participant, topic, writer or reader cannot be created: bad vendor name,
// bad domain id, or an error reported by the vendor library (its message is included).
// Never raised while reading or writing samples: those return false instead.
class DdsError : public std::runtime_error {
 public:
  explicit DdsError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace cover::dds
