#pragma once

#include <unistd.h>

#include <string>

namespace cover::test {

// A domain id and topic prefix of this test process's own, so that test binaries run in
// parallel by ctest never see each other's samples.
inline int private_domain_id() {
  return 1 + static_cast<int>(getpid() % 200);
}
inline std::string private_prefix(const std::string& name) {
  return "cover_test/" + name + "/p" + std::to_string(getpid());
}

}  // namespace cover::test
