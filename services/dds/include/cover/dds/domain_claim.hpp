#pragma once

#include <chrono>
#include <optional>

namespace cover::dds {

// Holds a DDS domain id on this host, so that two local runs (a test suite and a
// benchmark, two suites, two tests of one suite) never put their processes on the same
// domain, where one run's simulator ticks and commands would reach the other's agents.
// The claim is an abstract Unix socket named after the domain: the kernel frees it when
// its holder exits or crashes, and nothing is left in the filesystem. Children do not
// inherit it (close-on-exec). A claim is only a convention between local COVER runs:
// a participant that does not claim still joins the domain.
class DomainClaim {
 public:
  // `domain` if no other process holds it now.
  static std::optional<DomainClaim> try_claim(int domain);
  // `domain`, waiting for its holder to let go; throws std::runtime_error naming the
  // domain after `timeout`.
  static DomainClaim claim(int domain, std::chrono::milliseconds timeout);
  // The first free domain of [first, last], starting at a place that differs between
  // processes (so concurrent claimers rarely race for one); throws std::runtime_error
  // when all are held.
  static DomainClaim claim_any(int first, int last);

  DomainClaim(DomainClaim&& other) noexcept;
  DomainClaim& operator=(DomainClaim&& other) noexcept;
  DomainClaim(const DomainClaim&) = delete;
  DomainClaim& operator=(const DomainClaim&) = delete;
  ~DomainClaim();

  int domain() const { return domain_; }

 private:
  DomainClaim(int domain, int fd) : domain_(domain), fd_(fd) {}

  int domain_;
  int fd_;
};

}  // namespace cover::dds
