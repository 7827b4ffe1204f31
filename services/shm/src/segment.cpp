#include "cover/shm/segment.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spdlog/spdlog.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <new>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "cover/shm/segment_name.hpp"

namespace cover::shm {
namespace {

using Clock = std::chrono::steady_clock;

// How long a creator waits for another creator to finish a header it found incomplete
// before declaring it garbage: writing a header takes microseconds, so only a process
// that died between shm_open and publishing the magic exceeds this.
constexpr std::chrono::milliseconds kIncompleteHeaderGrace(250);
// How often a waiting reader or creator looks again.
constexpr std::chrono::milliseconds kPollPeriod(1);
// Replacing a stale segment races with other creators; give up after this many rounds.
constexpr int kCreateAttempts = 5;
// Readers may run as another user; only the owner can write.
constexpr mode_t kSegmentMode = 0644;

std::runtime_error system_error(const std::string& call, const std::string& name) {
  return std::runtime_error("shared-memory segment " + name + ": " + call +
                            " failed: " + std::strerror(errno));
}

void check_name(const std::string& name) {
  const bool valid = name.size() >= 2 && name.size() <= 255 && name.front() == '/' &&
                     name.find('/', 1) == std::string::npos;
  if (!valid) {
    throw std::invalid_argument("shared-memory segment name '" + name +
                                "' must be '/' followed by 1 to 254 characters without '/'");
  }
}

std::string hex(std::uint64_t value) {
  char text[19];
  std::snprintf(text, sizeof(text), "0x%016llx", static_cast<unsigned long long>(value));
  return text;
}

// What a creator finds under a name that already exists.
struct Existing {
  enum class State { kGone, kIncomplete, kGarbage, kDead, kAlive };
  State state = State::kGone;
  std::int32_t pid = 0;
  std::string detail;  // why it is stale, for the log
};

Existing inspect_header(const SegmentHeader& header, std::size_t size) {
  using State = Existing::State;
  const std::uint64_t magic = header.magic.load(std::memory_order_acquire);
  const std::int32_t pid = header.writer_pid;
  if (magic == 0) return {State::kIncomplete, pid, "its header was never completed"};
  if (magic != kSegmentMagic) return {State::kGarbage, pid, "its magic is " + hex(magic)};
  if (pid <= 0) return {State::kGarbage, pid, "its writer pid is " + std::to_string(pid)};
  if (size < kPayloadOffset + header.payload_size) {
    return {State::kGarbage, pid, "it is shorter than its payload"};
  }
  if (!process_alive(pid))
    return {State::kDead, pid, "writer pid " + std::to_string(pid) + " is dead"};
  return {State::kAlive, pid, ""};
}

Existing inspect(const std::string& name) {
  const int fd = shm_open(name.c_str(), O_RDONLY, 0);
  if (fd < 0) {
    if (errno == ENOENT) return {};
    throw system_error("shm_open (inspecting an existing segment)", name);
  }
  struct stat st {};
  const bool sized = fstat(fd, &st) == 0 && st.st_size >= static_cast<off_t>(kPayloadOffset);
  void* base = sized ? mmap(nullptr, kPayloadOffset, PROT_READ, MAP_SHARED, fd, 0) : MAP_FAILED;
  close(fd);
  if (base == MAP_FAILED) {
    return {Existing::State::kIncomplete, 0, "it is shorter than a header"};
  }
  Existing found = inspect_header(*static_cast<const SegmentHeader*>(base),
                                  static_cast<std::size_t>(st.st_size));
  munmap(base, kPayloadOffset);
  return found;
}

// Like inspect(), but gives a creator that is still filling its header time to finish.
Existing inspect_settled(const std::string& name) {
  const auto deadline = Clock::now() + kIncompleteHeaderGrace;
  while (true) {
    Existing found = inspect(name);
    if (found.state != Existing::State::kIncomplete || Clock::now() >= deadline) return found;
    std::this_thread::sleep_for(kPollPeriod);
  }
}

// Unlinks `name` if nobody alive owns it; throws if a live writer does.
void remove_if_stale(const std::string& name) {
  const Existing found = inspect_settled(name);
  switch (found.state) {
    case Existing::State::kGone:
      return;
    case Existing::State::kAlive:
      throw std::runtime_error("shared-memory segment " + name +
                               " is in use by a running writer, pid " + std::to_string(found.pid));
    default:
      spdlog::warn("removing stale shared-memory segment {}: {}", name, found.detail);
      if (shm_unlink(name.c_str()) != 0 && errno != ENOENT) throw system_error("shm_unlink", name);
  }
}

std::size_t segment_size(std::uint64_t payload_size) {
  return kPayloadOffset + static_cast<std::size_t>(payload_size);
}

// Sizes a segment just created as `fd` and maps it read-write; unlinks it and throws if
// either fails.
void* map_new(const std::string& name, int fd, std::size_t size) {
  void* base = ftruncate(fd, static_cast<off_t>(size)) == 0
                   ? mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0)
                   : MAP_FAILED;
  if (base != MAP_FAILED) return base;
  const std::runtime_error error = system_error("ftruncate/mmap", name);
  shm_unlink(name.c_str());
  close(fd);
  throw error;
}

void publish_header(void* base, std::uint32_t layout_version, std::uint64_t payload_size) {
  // ftruncate zero-filled the memory; the header's objects begin their lifetime here.
  auto* header = new (base) SegmentHeader{};
  header->layout_version = layout_version;
  header->writer_pid = static_cast<std::int32_t>(getpid());
  header->payload_size = payload_size;
  header->magic.store(kSegmentMagic, std::memory_order_release);  // publishes the rest
}

// Reasons a reader keeps waiting, for the timeout message.
constexpr const char* kAbsent = "does not exist";
constexpr const char* kNoHeader = "exists but its header is not complete";

// Maps `name` read-only if it exists and is at least a header long (its `size` set);
// nullptr otherwise, with `waiting_because` saying why.
void* map_for_reading(const std::string& name, std::size_t& size, const char*& waiting_because) {
  const int fd = shm_open(name.c_str(), O_RDONLY, 0);
  if (fd < 0) {
    if (errno == ENOENT) return nullptr;
    throw system_error("shm_open", name);
  }
  waiting_because = kNoHeader;
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    const std::runtime_error error = system_error("fstat", name);
    close(fd);
    throw error;
  }
  size = static_cast<std::size_t>(st.st_size);
  void* base =
      size >= kPayloadOffset ? mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0) : MAP_FAILED;
  close(fd);  // the mapping keeps the memory; a reader needs no descriptor
  return base == MAP_FAILED ? nullptr : base;
}

void check_header(const SegmentHeader& header, std::size_t size, const std::string& name,
                  std::uint32_t layout_version, std::uint64_t payload_size) {
  const std::uint64_t magic = header.magic.load(std::memory_order_acquire);
  if (magic != kSegmentMagic) {
    throw std::runtime_error("shared-memory segment " + name + " is not a COVER segment (magic " +
                             hex(magic) + ", expected " + hex(kSegmentMagic) + ")");
  }
  if (header.layout_version != layout_version) {
    throw std::runtime_error("shared-memory segment " + name + " has layout version " +
                             std::to_string(header.layout_version) + ", this reader expects " +
                             std::to_string(layout_version));
  }
  if (header.payload_size != payload_size) {
    throw std::runtime_error("shared-memory segment " + name + " has a payload of " +
                             std::to_string(header.payload_size) + " bytes, this reader expects " +
                             std::to_string(payload_size));
  }
  if (size < segment_size(payload_size)) {
    throw std::runtime_error("shared-memory segment " + name + " is " + std::to_string(size) +
                             " bytes, too short for its header and payload");
  }
}

}  // namespace

bool process_alive(std::int32_t pid) {
  return pid > 0 && (kill(pid, 0) == 0 || errno != ESRCH);
}

Segment::Segment(std::string name, int fd, void* base, std::size_t size, bool owner)
    : name_(std::move(name)), fd_(fd), base_(base), size_(size), owner_(owner) {}

Segment Segment::create(const std::string& name, std::uint32_t layout_version,
                        std::uint64_t payload_size) {
  check_name(name);
  for (int attempt = 0; attempt < kCreateAttempts; ++attempt) {
    const int fd = shm_open(name.c_str(), O_CREAT | O_EXCL | O_RDWR, kSegmentMode);
    if (fd < 0) {
      if (errno != EEXIST) throw system_error("shm_open", name);
      remove_if_stale(name);
      continue;
    }
    const std::size_t size = segment_size(payload_size);
    void* base = map_new(name, fd, size);
    publish_header(base, layout_version, payload_size);
    return Segment(name, fd, base, size, true);
  }
  throw std::runtime_error("shared-memory segment " + name + ": another process recreated it " +
                           std::to_string(kCreateAttempts) + " times while replacing it");
}

Segment Segment::open(const std::string& name, std::uint32_t layout_version,
                      std::uint64_t payload_size, std::chrono::milliseconds wait) {
  check_name(name);
  const auto deadline = Clock::now() + wait;
  while (true) {
    const char* waiting_because = kAbsent;
    std::size_t size = 0;
    if (void* base = map_for_reading(name, size, waiting_because)) {
      Segment segment(name, -1, base, size, false);
      if (segment.header().magic.load(std::memory_order_acquire) != 0) {
        check_header(segment.header(), size, name, layout_version, payload_size);
        return segment;
      }
    }
    if (Clock::now() >= deadline) {
      throw std::runtime_error("shared-memory segment " + name + " " + waiting_because +
                               " after waiting " + std::to_string(wait.count()) + " ms");
    }
    std::this_thread::sleep_for(kPollPeriod);
  }
}

Segment::~Segment() {
  release();
}

Segment::Segment(Segment&& other) noexcept
    : name_(std::move(other.name_)),
      fd_(std::exchange(other.fd_, -1)),
      base_(std::exchange(other.base_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      owner_(std::exchange(other.owner_, false)) {}

Segment& Segment::operator=(Segment&& other) noexcept {
  if (this != &other) {
    release();
    name_ = std::move(other.name_);
    fd_ = std::exchange(other.fd_, -1);
    base_ = std::exchange(other.base_, nullptr);
    size_ = std::exchange(other.size_, 0);
    owner_ = std::exchange(other.owner_, false);
  }
  return *this;
}

SegmentHeader& Segment::writable_header() {
  if (!owner_) throw std::logic_error("shared-memory segment " + name_ + " is mapped read-only");
  return *static_cast<SegmentHeader*>(base_);
}

std::byte* Segment::writable_payload() {
  if (!owner_) throw std::logic_error("shared-memory segment " + name_ + " is mapped read-only");
  return static_cast<std::byte*>(base_) + kPayloadOffset;
}

void Segment::release() noexcept {
  if (base_ != nullptr) munmap(base_, size_);
  base_ = nullptr;
  if (owner_) {
    // Unlink only our own segment: if someone replaced the name meanwhile (it judged us
    // stale), removing theirs would break their readers.
    struct stat mine {};
    struct stat named {};
    const bool same = fstat(fd_, &mine) == 0 && stat(segment_path(name_).c_str(), &named) == 0 &&
                      mine.st_dev == named.st_dev && mine.st_ino == named.st_ino;
    if (same) shm_unlink(name_.c_str());
  }
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  owner_ = false;
}

bool remove_segment(const std::string& name) {
  check_name(name);
  if (shm_unlink(name.c_str()) == 0) return true;
  if (errno == ENOENT) return false;
  throw system_error("shm_unlink", name);
}

}  // namespace cover::shm
