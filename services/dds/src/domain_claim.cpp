#include "cover/dds/domain_claim.hpp"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>

namespace cover::dds {

namespace {

constexpr std::chrono::milliseconds kRetryPeriod{50};

// A bound abstract socket for `domain`, or -1 when another process holds it.
int bind_claim_socket(int domain) {
  const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("domain claim: socket: ") + strerror(errno));
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string name = "cover-dds-domain-" + std::to_string(domain);
  // Abstract namespace: a leading NUL, the name not NUL-terminated.
  std::memcpy(address.sun_path + 1, name.data(), name.size());
  const auto length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + name.size());
  if (bind(fd, reinterpret_cast<const sockaddr*>(&address), length) == 0) return fd;
  const int error = errno;
  close(fd);
  if (error == EADDRINUSE) return -1;
  throw std::runtime_error("domain claim: bind for domain " + std::to_string(domain) + ": " +
                           strerror(error));
}

}  // namespace

std::optional<DomainClaim> DomainClaim::try_claim(int domain) {
  const int fd = bind_claim_socket(domain);
  if (fd < 0) return std::nullopt;
  return DomainClaim(domain, fd);
}

DomainClaim DomainClaim::claim(int domain, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (auto held = try_claim(domain)) return std::move(*held);
    if (std::chrono::steady_clock::now() >= deadline) {
      throw std::runtime_error("DDS domain " + std::to_string(domain) +
                               " is still held by another local COVER run after " +
                               std::to_string(timeout.count()) + " ms");
    }
    std::this_thread::sleep_for(kRetryPeriod);  // polling another process's release
  }
}

DomainClaim DomainClaim::claim_any(int first, int last) {
  if (first > last) throw std::invalid_argument("domain claim: empty range");
  const int count = last - first + 1;
  const int start = static_cast<int>(getpid() % count);
  for (int i = 0; i < count; ++i) {
    const int domain = first + (start + i) % count;
    if (auto held = try_claim(domain)) return std::move(*held);
  }
  throw std::runtime_error("every DDS domain of " + std::to_string(first) + ".." +
                           std::to_string(last) + " is held by another local COVER run");
}

DomainClaim::DomainClaim(DomainClaim&& other) noexcept : domain_(other.domain_), fd_(other.fd_) {
  other.fd_ = -1;
}

DomainClaim& DomainClaim::operator=(DomainClaim&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) close(fd_);
    domain_ = other.domain_;
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

DomainClaim::~DomainClaim() {
  if (fd_ >= 0) close(fd_);
}

}  // namespace cover::dds
