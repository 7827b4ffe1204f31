// The MCAP reader (cover_mcap's Reader) behind `cover bag info` and `cover play`, fed any
// file: a recording cut by a crash, a corrupt disk, a foreign file renamed .mcap.
// Contract: no crash and no allocation beyond the reader's limits; every delivered message
// has a known channel and lies inside the file's size; a scan that returns true read the
// file to its closing magic without an issue; every issue's offset is inside the file; a
// second scan of the same bytes gives the same messages and issues.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <string>
#include <vector>

#include "cover/mcap/reader.hpp"
#include "fuzz_input.hpp"

namespace {

using cover::fuzz::require;

struct Scan {
  std::vector<std::uint64_t> log_times;
  std::vector<std::uint64_t> issue_offsets;
  std::size_t bytes = 0;
};

Scan scan(const std::string& path, std::uint64_t file_size) {
  Scan result;
  cover::mcap::Reader reader(path);
  const bool complete = reader.scan([&](const cover::mcap::MessageView& m) {
    require(m.channel != nullptr, "a message without its channel");
    require(reader.channels().count(m.channel->id) == 1, "a message of an unknown channel");
    require(m.size <= file_size * 1024 + 1024, "a message larger than the file could hold");
    result.log_times.push_back(m.header.log_time_ns);
    result.bytes += m.size;
    return true;
  });
  require(!complete || (reader.issues().empty() && reader.finished()),
          "a complete scan with issues or without its footer");
  require(complete || !reader.issues().empty(), "an incomplete scan without an issue");
  for (const auto& issue : reader.issues()) {
    require(issue.offset <= file_size, "an issue's offset past the end of the file");
    require(!issue.what.empty(), "an issue that says nothing");
    result.issue_offsets.push_back(issue.offset);
  }
  return result;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The reader opens a path: an anonymous memory file keeps the fuzzer off the disk.
  const int fd = memfd_create("fuzz_mcap", 0);
  if (fd < 0) return 0;
  std::size_t written = 0;
  while (written < size) {
    const ssize_t n = write(fd, data + written, size - written);
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  const Scan first = scan(path, size);
  const Scan second = scan(path, size);
  require(first.log_times == second.log_times && first.issue_offsets == second.issue_offsets,
          "two scans of the same bytes differ");
  close(fd);
  return 0;
}
