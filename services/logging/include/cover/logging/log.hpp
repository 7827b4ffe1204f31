#pragma once

#include <spdlog/spdlog.h>

#include <string>

namespace cover::logging {

// Configures the process-wide logger: `process_name` prefixes every line, `level` is one
// of trace|debug|info|warn|error|off (or the COVER_LOG_LEVEL environment variable).
// Logs go to stderr so stdout stays clean for JSON output of the tools.
void init(const std::string& process_name, const std::string& level = "");

// Also writes every line of the process-wide logger to `path` (appended, no colours), for
// processes whose decisions must be kept with the run, e.g. the launcher's launch.log.
// Call after init(). Throws spdlog::spdlog_ex when the file cannot be opened.
void add_file(const std::string& path);

}  // namespace cover::logging
