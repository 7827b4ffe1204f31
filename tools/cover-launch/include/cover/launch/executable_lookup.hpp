#pragma once

#include <optional>
#include <string>

namespace cover::launch {

// Where an `executable:` of a launch file is. A name with '/' is a path, relative to the
// launch file's folder `launch_dir`; a bare name is looked for in `self_dir` (where
// cover-launch itself is, beside the other COVER executables), then in every folder of
// `search_path` (colon-separated, like $PATH). nullopt when nothing executable is found.
std::optional<std::string> resolve_executable(const std::string& executable,
                                              const std::string& launch_dir,
                                              const std::string& self_dir,
                                              const std::string& search_path);

// The folder of the running executable (dirname of /proc/self/exe).
std::string self_executable_dir();

}  // namespace cover::launch
