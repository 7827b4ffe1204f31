#pragma once

#include <string>

namespace cover::shm {

// The shared-memory name of one simulator run: "/cover_sim_d<domain>_<run_id>". The DDS
// domain is part of it so that runs on different domains on one host never share a
// segment. Throws std::invalid_argument when the domain is outside 0..232 or `run_id`
// does not match [A-Za-z0-9_]{1,40}.
std::string segment_name(int dds_domain, const std::string& run_id);

// Where Linux shows a segment in the file system: "/dev/shm/<name without its slash>".
// For tests and launchers that look for or clean up segments.
std::string segment_path(const std::string& name);

}  // namespace cover::shm
