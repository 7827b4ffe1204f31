// DomainClaim: one holder per domain on this host, released when the holder goes.
#include "cover/dds/domain_claim.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>

#include "dds_test_support.hpp"

namespace {

using cover::dds::DomainClaim;
using namespace std::chrono_literals;

// A domain no one holds now, from 221..232: outside the DDS tests' private range and
// every fixed test or benchmark domain.
int spare_domain() {
  for (int d = 232; d > 220; --d) {
    if (DomainClaim::try_claim(d)) return d;
  }
  ADD_FAILURE() << "no free domain in 221..232";
  return 232;
}

TEST(DomainClaim, ADomainHasOneHolderUntilItLetsGo) {
  const int domain = spare_domain();
  {
    auto first = DomainClaim::try_claim(domain);
    ASSERT_TRUE(first.has_value());
    EXPECT_EQ(first->domain(), domain);
    EXPECT_FALSE(DomainClaim::try_claim(domain).has_value());
    EXPECT_THROW(DomainClaim::claim(domain, 100ms), std::runtime_error);
    DomainClaim moved = std::move(*first);
    EXPECT_FALSE(DomainClaim::try_claim(domain).has_value()) << "a move let go of the claim";
  }
  EXPECT_TRUE(DomainClaim::try_claim(domain).has_value());
}

TEST(DomainClaim, AnotherProcessSeesTheClaimAndGetsItOnceTheHolderDies) {
  const int domain = spare_domain();
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t holder = fork();
  ASSERT_GE(holder, 0);
  if (holder == 0) {
    auto claim = DomainClaim::try_claim(domain);
    const char byte = claim ? 1 : 0;
    if (write(ready[1], &byte, 1) != 1) _exit(2);
    pause();  // held until killed: the kernel must free it
    _exit(0);
  }
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1);
  ASSERT_EQ(byte, 1);
  EXPECT_FALSE(DomainClaim::try_claim(domain).has_value());
  kill(holder, SIGKILL);
  waitpid(holder, nullptr, 0);
  EXPECT_NO_THROW(DomainClaim::claim(domain, 5s));
  close(ready[0]);
  close(ready[1]);
}

TEST(DomainClaim, PrivateDomainsComeFromTheDdsTestsRange) {
  const int domain = cover::test::private_domain_id();
  EXPECT_GE(domain, cover::test::kFirstPrivateDomain);
  EXPECT_LE(domain, cover::test::kLastPrivateDomain);
  EXPECT_EQ(cover::test::private_domain_id(), domain);
  EXPECT_FALSE(DomainClaim::try_claim(domain).has_value());
  EXPECT_THROW(DomainClaim::claim_any(domain, domain), std::runtime_error);
}

}  // namespace
